"""Contact modes (docs/physics-modes.md): laws on rolling and spinning as data, their maps C_m and
mobilities mu_m, the zero-current lemma of each mode, and of several modes on one pair."""

import dataclasses

import pytest
import sympy as sp

from fricgen.derive import derive_noise, driver, load_law, make_law, verify
from fricgen.derive.calculus import Calculus
from fricgen.derive.law.law_files import law_text
from fricgen.derive.law.lawdata import CONTACT_MODES, ModeError, mode_refusal
from fricgen.derive.law.laws import LawError
from fricgen.derive.noise import lemma_cache, mode_proofs, modes
from fricgen.derive.noise.contact import coupling, prove_contact
from fricgen.derive.noise.phase_space import pair_phase_space

CASES = [(m, d) for m, dims in CONTACT_MODES.items() for d in dims]
ROLLING = """name = "rolling_linear"
friction = "gamma_r*u"
mode = "rolling"

[parameters.gamma_r]
default = 2.0
"""


# --- laws on a mode, as data ----------------------------------------------------------------------


def test_a_law_file_names_its_mode_and_sliding_is_the_default(tmp_path, laws):
    path = tmp_path / "rolling_linear.toml"
    path.write_text(ROLLING)
    law = load_law(path)
    assert law.mode == "rolling"
    assert law_text(law).count('mode = "rolling"') == 1
    sliding = [law for law in laws.values() if law.mode == "sliding"]
    assert sliding and all("mode" not in law_text(law) for law in sliding)  # the default is not written
    assert laws["rolling_coulomb_newton"].mode == "rolling"  # the catalogue's rolling law
    assert law_text(laws["rolling_coulomb_newton"]).count('mode = "rolling"') == 1


@pytest.mark.parametrize(
    ("line", "message"),
    [
        ('mode = "twisting"', "mode: unknown contact mode 'twisting'; allowed: ['sliding', 'rolling', 'spinning']"),
        ("mode = 3", "mode must be a string, got int 3"),
        ('mode = "' + "x" * 100 + '"', "mode: unknown contact mode str 'xxxxx"),
    ],
)
def test_an_unknown_mode_is_refused_on_one_line(tmp_path, line, message):
    path = tmp_path / "rolling_linear.toml"
    path.write_text(ROLLING.replace('mode = "rolling"', line))
    with pytest.raises(LawError) as error:
        load_law(path)
    assert message in str(error.value) and "\n" not in str(error.value)


def test_make_law_checks_the_mode():
    assert make_law("r", "u", mode="spinning").mode == "spinning"
    with pytest.raises(LawError, match="law r: mode: unknown contact mode 'roll'"):
        make_law("r", "u", mode="roll")


def test_spinning_does_not_exist_in_2d():
    why = mode_refusal("spinning", 2)
    assert why.startswith("the spinning mode exists in 3-D only, not in 2-D") and "\n" not in why
    assert mode_refusal("rolling", 2) == mode_refusal("spinning", 3) == ""
    with pytest.raises(ModeError, match="3-D only"):
        modes.describe("spinning", 2)


def test_a_rolling_laws_module_states_its_mode_and_a_backend_without_the_mode_refuses_it(tmp_path):
    """The Numba kernels of a rolling law carry MODE = 'rolling' (a sliding law's module has no MODE and is
    unchanged); the LAMMPS plugin emits every mode; a backend that applies sliding only would refuse the law."""
    path = tmp_path / "rolling_linear.toml"
    path.write_text(ROLLING)
    law = dataclasses.replace(load_law(path), calculi=("ito",))
    assert driver.PLUGIN_MODES == driver.EMITTED_MODES == ("sliding", "rolling", "spinning")
    with pytest.raises(
        driver.GenerationError, match=r"mode 'rolling': the sliding backend emits no kernels for it \(it applies \['sliding'\]\)"
    ):
        driver.verified_models(law, emitted=("sliding",), backend="sliding")
    models, _ = driver.verified_models(law)
    text = driver.stating_mode(driver.law_module(law, models, law.source_hash, "rolling_linear.toml"), law.mode)
    assert text.count("\nMODE = 'rolling'  # the contact mode") == 1 and text.index("\nHAS_WEIGHT") < text.index("\nMODE")
    plain = driver.law_module(law, models, law.source_hash, "rolling_linear.toml")
    assert driver.stating_mode(plain, "sliding") == plain and "\nMODE" not in plain


# --- the maps C_m and the mobilities mu_m ---------------------------------------------------------


@pytest.mark.parametrize(("mode", "dim"), CASES)
def test_mode_facts(mode, dim):
    """v_m = C_m v; forces and torques -C_m^T v_m f/u, power -f u; covariance kT D C_m^T C_m;
    C_m M^-1 C_m^T = mu_m x projector, mu_m read off and equal to the engines' formula."""
    facts = mode_proofs.mode_facts(mode, dim)
    assert facts and all(facts.values()), facts


def test_mobilities_read_off_C_M_CT():
    space = pair_phase_space(3)
    m_i, m_k, inertia_i, inertia_k = space.masses
    radius_i, radius_k = space.radii
    reduced = radius_i * radius_k / (radius_i + radius_k)
    expected = {"sliding": 1 / m_i + 1 / m_k + radius_i**2 / inertia_i + radius_k**2 / inertia_k, "rolling": None, "spinning": None}
    expected["rolling"] = expected["spinning"] = reduced**2 * (1 / inertia_i + 1 / inertia_k)
    for mode, dim in CASES:
        mobility, rank = mode_proofs.read_mobility(mode, dim)
        assert sp.simplify(mobility - expected[mode]) == 0
        assert rank == (2 if dim == 3 and mode != "spinning" else 1)
    assert modes.mode_mobility("rolling", 1, 1, 0.5, 0.5) == sp.Rational(5, 4)  # equal solid spheres: R^2/(2I)
    assert modes.mode_mobility("sliding", 1, 1, 0.5, 0.5) == 7


def mutated(monkeypatch, **change):
    """mode_proofs sees every mode with ``change(mode)`` applied to its fields (a wrong description)."""
    describe = modes.describe
    monkeypatch.setattr(mode_proofs, "describe", lambda *a: dataclasses.replace(m := describe(*a), **{k: f(m) for k, f in change.items()}))


@pytest.mark.parametrize("mode", ["sliding", "rolling"])
def test_a_mobility_formula_off_by_a_factor_is_refuted(monkeypatch, mode):
    mutated(monkeypatch, mobility=lambda m: 2 * m.mobility)
    assert not mode_proofs.mode_facts.__wrapped__(mode, 3)["mobility_formula"]


def test_the_papers_random_force_is_a_written_form_of_the_sliding_noise(monkeypatch):
    """Sliding in 3-D has two written noises, sigma_hat and (F-24, F-25); a sign slip in the latter is refuted."""
    assert len(modes.describe("sliding", 3).noises) == 2
    slip = sp.Symbol("n_z", real=True)
    mutated(monkeypatch, noises=lambda m: (m.noises[0], *(g.subs(slip, 0) for g in m.noises[1:])))
    assert not mode_proofs.mode_facts.__wrapped__("sliding", 3)["noise_covariance"]


def test_sliding_and_rolling_couple_for_unequal_spheres_only():
    """C_s M^-1 C_r^T = R_eff (R_k/I_k - R_i/I_i) P; spinning is orthogonal to both."""
    space = pair_phase_space(3)
    _, _, inertia_i, inertia_k = space.masses
    radius_i, radius_k = space.radii
    scalar = radius_i * radius_k / (radius_i + radius_k) * (radius_k / inertia_k - radius_i / inertia_i)
    matrix = mode_proofs.mobility_matrix(space, "sliding", "rolling")
    n = sp.Matrix(space.normal)
    assert all(space.reduce(sp.numer(sp.together(e))) == 0 for e in matrix - scalar * (sp.eye(3) - n * n.T))
    assert matrix.subs({radius_k: radius_i, inertia_k: inertia_i}) == sp.zeros(3)
    assert coupling("sliding", "spinning", 3) == coupling("rolling", "spinning", 3) == "0"
    names = {str(x): x for x in (*space.masses, *space.radii)}
    assert sp.simplify(sp.sympify(coupling("sliding", "rolling", 2), locals=names) - scalar) == 0


# --- the zero-current lemma of each mode, and of several modes --------------------------------------


def one_minus_theta(calculus):
    value = 1 - Calculus(calculus).theta
    return sp.Rational(value.numerator, value.denominator)


@pytest.mark.parametrize(("mode", "dim"), [c for c in CASES if c != ("sliding", 3)])
@pytest.mark.parametrize("calculus", ["ito", "stratonovich", "hk"])
def test_zero_current_lemma_of_a_mode(mode, dim, calculus):
    """Sliding in 3-D: tests/symbolic/test_phase_space.py."""
    lemma = mode_proofs.zero_current(mode, dim, calculus)
    assert lemma.holds and lemma.nu_over_mu == one_minus_theta(calculus)


def test_the_lemma_reads_nu_kT_off_the_current(monkeypatch):
    """A rolling noise without its kT: the coefficient of D' is mu_m, not mu_m kT, and the lemma fails."""
    mutated(monkeypatch, noises=lambda m: tuple(s / sp.sqrt(sp.Symbol("kT", positive=True)) for s in m.noises))
    assert not mode_proofs.zero_current.__wrapped__("rolling", 3, "ito").holds


def test_a_torque_on_one_sphere_only_is_refuted(monkeypatch):
    """The rolling couple applied to sphere i alone: not C_r^T, and it does not dissipate f u."""
    mutated(monkeypatch, drag=lambda m: m.drag - _k_block(m.drag))
    facts = mode_proofs.mode_facts.__wrapped__("rolling", 3)
    assert not facts["forces_from_C_transpose"] and not facts["dissipation"]
    assert not mode_proofs.zero_current.__wrapped__("rolling", 3, "ito").holds


def _k_block(vector):
    """The torque on sphere k alone (the last 3 of 12 components)."""
    return sp.Matrix([0] * 9 + list(vector[9:]))


@pytest.mark.parametrize("calculus", ["ito", "stratonovich", "hk"])
def test_sliding_and_rolling_together_in_2d(calculus):
    result = mode_proofs.combined_current(("sliding", "rolling"), 2, calculus)
    assert result["holds"] and set(result["nu_over_mu"].values()) == {one_minus_theta(calculus)}


@pytest.mark.parametrize("calculus", ["ito", "stratonovich", "hk"])
def test_all_three_modes_together_in_3d(calculus):
    """With masses, inertias and radii unequal: the modes couple (sliding-rolling), the current of
    the sum is still the sum of the modes' currents."""
    assert mode_proofs.combined_current(("sliding", "rolling", "spinning"), 3, calculus)["holds"]


@pytest.mark.parametrize(("mode_set", "dim"), [(("sliding", "rolling"), 2), (("rolling", "spinning"), 3)])
def test_a_noise_shared_between_modes_is_refuted(mode_set, dim):
    assert mode_proofs.combined_current(mode_set, dim, "ito")["holds"]
    assert not mode_proofs.combined_current(mode_set, dim, "ito", shared=True)["holds"]


# --- verify: one law per mode, and a pair's set of laws -------------------------------------------


@pytest.fixture(scope="module")
def mode_laws(laws):
    return {
        "rolling": dataclasses.replace(laws["coulomb_newton"], name="rolling_cn", mode="rolling"),
        "spinning": dataclasses.replace(laws["linear"], name="spinning_linear", mode="spinning"),
    }


@pytest.mark.parametrize("mode", ["rolling", "spinning"])
@pytest.mark.parametrize("calculus", ["ito", "stratonovich", "hk"])
def test_verify_proves_a_law_on_each_mode(mode_laws, mode, calculus):
    report = verify(derive_noise(mode_laws[mode], calculus))
    assert report.verified, (report.checks, report.details)
    dims = ["3d"] if mode == "spinning" else ["3d", "2d"]
    assert {f"zero_current_{d}" for d in dims} | {"contact_mode", "kernel_accuracy"} <= set(report.checks)
    assert ("zero_current_2d" in report.checks) == (mode != "spinning")


def test_verify_contact_accepts_one_law_per_mode_and_says_how_modes_couple(laws, mode_laws):
    models = [derive_noise(law, "ito") for law in (laws["coulomb_newton"], mode_laws["rolling"], mode_laws["spinning"])]
    report = driver.verify_contact(models)
    assert report.verified, report.reason
    assert set(report.checks) >= {"zero_current_3d", "laws_verified"} and "zero_current_2d" not in report.checks
    assert "P" in report.details["coupling sliding-rolling 3d"] and report.details["coupling rolling-spinning 3d"] == "0"


@pytest.mark.parametrize(
    ("pick", "calculi", "dims", "reason"),
    [
        (("sliding", "spinning"), ("ito", "ito"), (2,), "modes_exist: the spinning mode exists in 3-D only"),
        (("sliding", "sliding"), ("ito", "ito"), None, "one_law_per_mode"),
        (("sliding", "rolling"), ("ito", "stratonovich"), None, "one_calculus"),
    ],
)
def test_verify_contact_refuses_with_the_reason(laws, mode_laws, pick, calculi, dims, reason):
    chosen = {"sliding": laws["coulomb_newton"], **mode_laws}
    report = prove_contact([derive_noise(chosen[m], c) for m, c in zip(pick, calculi)], dims)
    assert not report.verified and report.reason.startswith(reason) and "\n" not in report.reason


def test_a_mode_law_with_a_wrong_amplitude_fails_verify_contact(laws, mode_laws):
    rolling = derive_noise(mode_laws["rolling"], "ito")
    wrong = dataclasses.replace(rolling, amplitude=sp.Rational(101, 100) * rolling.amplitude)
    report = prove_contact([derive_noise(laws["coulomb_newton"], "ito"), wrong], dims=(2,))
    assert not report.verified and report.reason.startswith("laws_verified: rolling_cn (ito)")


@pytest.mark.parametrize("entry", [{"holds": True, "nu_over_mu": "1"}, {"holds": False, "nu_over_mu": "1/2"}, {"holds": True}])
def test_the_lemma_cache_keeps_only_what_the_proof_establishes(lemma_cache_folder, monkeypatch, entry):
    """An entry of a mode's lemma is used only if it states the proven lemma (holds, nu/mu = 1 - theta);
    a vacuous, negative or foreign one is proven again and rewritten. The key covers modes.py and mode_proofs.py."""
    calls, prove = [], mode_proofs.zero_current
    monkeypatch.setattr(mode_proofs, "zero_current", lambda *args: calls.append(args) or prove(*args))
    assert {p.name for p in lemma_cache.SOURCES} >= {"phase_space.py", "modes.py", "mode_proofs.py", "lemma_cache.py"}
    name = "zero_current_rolling_2d_stratonovich"
    lemma_cache.lemma.cache_clear()
    assert lemma_cache.lemma("rolling", 2, "stratonovich").nu_over_mu == sp.Rational(1, 2)
    lemma_cache.lemma.cache_clear()
    assert lemma_cache.lemma("rolling", 2, "stratonovich").nu_over_mu == sp.Rational(1, 2)
    proven = len(calls)  # 1 with a fresh cache folder, 0 if an earlier test stored the entry
    lemma_cache.write_entry(name, entry)
    lemma_cache.lemma.cache_clear()
    assert lemma_cache.lemma("rolling", 2, "stratonovich").nu_over_mu == sp.Rational(1, 2)
    assert len(calls) == proven + 1
    assert lemma_cache.read_entry(name) == {"holds": True, "nu_over_mu": "1/2"}
