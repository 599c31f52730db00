"""A failed proof says what is wrong in words a user can act on."""

from fricgen.derive import derive_noise, make_law, verify


def test_a_jump_of_f_under_hk_is_named_with_its_place_and_the_fix():
    law = make_law("jumpy", "Piecewise((gamma_f*u, u < 1), (2*gamma_f*u, True))", {"gamma_f": {"default": 1.0}})
    assert verify(derive_noise(law, "ito")).verified  # the integral (F-22) smooths the jump
    report = verify(derive_noise(law, "hk"))
    assert not report.verified and not report.checks["ode_residual"]
    message = report.details["ode_residual"]
    assert "D jumps by gamma_f at u = 1" in message and "leave hk out" in message and "\n" not in message
