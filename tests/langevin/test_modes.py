"""Rolling and spinning friction in the engine (docs/physics-modes.md): each law acts on its own contact
mode with the noise derived for it, and the pairwise step keeps Maxwell–Boltzmann.

Laws of one's own (a folder generated once per module): linear rolling f = gamma_r u and linear spinning
f = gamma_s u (D = gamma in every calculus), beside the built-in Coulomb–Newton on sliding. The fluids
mix two kinds of sphere (radii 0.5 and 0.4, masses 1 and 0.7, I = 2/5 m R^2), so that R_eff, mu_m and the
sliding-rolling coupling are those of unequal spheres. "At kT" means T_trans and T_rot within 4 block
standard errors; a mode without its noise cools the spins by many errors (the negative controls).
"""

import dataclasses
import os
import subprocess
import sys
import textwrap
import types

import numba
import numpy as np
import pytest

import fricgen
from fricgen.derive.driver import generate
from fricgen.errors import ConfigError
from fricgen.kernels import CONTACT_KERNEL, LawKernels
from fricgen.langevin import Particles, Simulation, State, lattice_state
from fricgen.langevin.analysis import Sampler, block_estimate

from .helpers import arrays, config

ROLLING = """name = "rolling_linear"
description = "Linear rolling friction f = gamma_r u, u the rolling speed; D = gamma_r."
friction = "gamma_r*u"
mode = "rolling"
calculi = ["ito"]

[parameters.gamma_r]
default = 5.0
unit = "t0/sigma"
"""
SPINNING = ROLLING.replace("rolling", "spinning").replace("gamma_r", "gamma_s")
#: A held-out nonlinear law (not written with the engine in mind): saturating spinning friction, whose Ito and
#: Stratonovich D have no closed form (integral form, tables per mobility).
SOFT = """name = "spinning_soft"
description = "A saturating spinning friction f = gamma_s u / (1 + u / u0), u the spinning speed."
friction = "gamma_s*u/(1 + u/u0)"
mode = "spinning"
calculi = ["ito", "stratonovich", "hk"]

[parameters.gamma_s]
default = 5.0
unit = "t0/sigma"

[parameters.u0]
default = 0.5
unit = "sigma/t0"
"""


@pytest.fixture(scope="module")
def laws(tmp_path_factory):
    """The kernels of the rolling and spinning laws, generated into a folder of one's own."""
    folder = tmp_path_factory.mktemp("modes") / "laws"
    folder.mkdir()
    (folder / "rolling_linear.toml").write_text(ROLLING)
    (folder / "spinning_linear.toml").write_text(SPINNING)
    (folder / "spinning_soft.toml").write_text(SOFT)
    generate(catalogue=folder)
    own = {name: fricgen.load_law(name, folder=folder) for name in ("rolling_linear", "spinning_linear", "spinning_soft")}
    return own | {name: fricgen.load_law(name) for name in ("coulomb_newton", "rolling_coulomb_newton")}


def mixture(n: int) -> Particles:
    """n spheres, every other one of radius 0.4 and mass 0.7 (the rest 0.5 and 1), I = 2/5 m R^2."""
    radius, mass = np.where(np.arange(n) % 2, 0.4, 0.5), np.where(np.arange(n) % 2, 0.7, 1.0)
    return Particles(radius, mass, 0.4 * mass * radius**2, np.ones(n, dtype=bool))


def simulation(laws, names, dim=3, n=64, seed=5, solvent=True, **options) -> Simulation:
    """A fluid of the mixture (area fraction 0.5 in 2-D, volume fraction 0.3 in 3-D) with the laws ``names``
    (the first as law.name, then a rolling and a spinning one as law.rolling, law.spinning)."""
    first, *others = names
    modes = {laws[name].mode: name for name in others}
    thermostat = {} if solvent else {"gamma": 0.0, "gamma_rot": 0.0}
    c = config(first, seed=seed, **modes, **thermostat, **options)
    particles = mixture(n)
    state = lattice_state(particles, dim, 0.5 if dim == 2 else 0.3, seed=seed)
    return Simulation(c, particles, state, [laws[name] for name in names])


def temperatures(sim: Simulation, total: float) -> tuple[float, float, float, float]:
    """(T_trans, error, T_rot, error) over ``total`` t0 after 10 % equilibration, a sample every 0.02 t0."""
    dt = sim.config.thermostat.dt
    steps, every = int(round(total / dt)), max(1, int(round(0.02 / dt)))
    sim.threads = 1
    sim.run(steps // 10, every=steps // 10)
    sampler = Sampler(sim.particles)
    sim.run(steps - steps // 10, every=every, observers=[sampler])
    trans, rot = block_estimate(sampler.trans, 20), block_estimate(sampler.rot, 20)
    return trans.mean, trans.error, rot.mean, rot.error


def at_kT(t_trans, e_trans, t_rot, e_rot) -> bool:
    return abs(t_trans - 1) <= 4 * e_trans and abs(t_rot - 1) <= 4 * e_rot


CASES = [
    # names, dim, solvent, total time (t0)
    (("rolling_linear",), 2, True, 20.0),
    (("rolling_linear",), 3, True, 10.0),
    (("spinning_linear",), 3, True, 10.0),
    (("coulomb_newton", "rolling_linear"), 2, False, 20.0),
    (("coulomb_newton", "rolling_linear"), 2, True, 20.0),
    (("coulomb_newton", "rolling_linear", "spinning_linear"), 3, False, 10.0),
    (("coulomb_newton", "rolling_linear", "spinning_linear"), 3, True, 10.0),
]


@pytest.mark.parametrize(("names", "dim", "solvent", "total"), CASES, ids=lambda x: str(x))
def test_the_pairwise_step_of_every_mode_keeps_kT(laws, names, dim, solvent, total):
    """dt = 1e-3, unequal spheres: the mixture stays at kT in translation and rotation."""
    result = temperatures(simulation(laws, names, dim=dim, solvent=solvent), total)
    assert at_kT(*result), result


@pytest.mark.parametrize(("name", "dim"), [("rolling_linear", 2), ("rolling_linear", 3), ("spinning_linear", 3)])
def test_a_mode_without_its_noise_cools_the_spins(laws, name, dim):
    """The negative control: the mode's friction alone (gamma = 50, solvent kept) takes the rotation below kT."""
    stiff = {"gamma_r" if name.startswith("rolling") else "gamma_s": 50.0}
    t_trans, e_trans, t_rot, e_rot = temperatures(simulation(laws, (name,), dim=dim, contact_noise=False, parameters=stiff), 10.0)
    assert abs(t_trans - 1) <= 4 * e_trans  # a pure couple: translation keeps the solvent's kT
    assert t_rot < 1 - 10 * e_rot, (t_rot, e_rot)


def test_the_explicit_kick_of_every_mode_keeps_kT_and_cools_without_the_noise(laws):
    """The explicit kick applies the modes' friction and noise too (a wrong D would show here): all three
    modes in 3-D at dt = 5e-4 (a kick bias of mu_m D dt / 2 below the error), and without the noise it cools."""
    names = ("coulomb_newton", "rolling_linear", "spinning_linear")
    result = temperatures(simulation(laws, names, contact_scheme="explicit", dt=5e-4), 5.0)
    assert at_kT(*result), result
    cold = temperatures(simulation(laws, names, contact_scheme="explicit", dt=5e-4, contact_noise=False), 5.0)
    assert cold[2] < 1 - 10 * cold[3], cold


def test_nonlinear_mode_laws_keep_kT_in_the_explicit_kick(laws):
    """Nonlinear laws on every mode, their D checked where a wrong one shows: the catalogue's rolling
    Coulomb–Newton (a kink, a weight) and the held-out saturating spinning law (D in integral form), all
    three modes in 3-D, explicit kick at dt = 5e-4; without their noise the spins cool."""
    names = ("coulomb_newton", "rolling_coulomb_newton", "spinning_soft")
    result = temperatures(simulation(laws, names, contact_scheme="explicit", dt=5e-4), 5.0)
    assert at_kT(*result), result
    cold = temperatures(simulation(laws, names, contact_scheme="explicit", dt=5e-4, rolling_noise=False, spinning_noise=False), 5.0)
    assert cold[2] < 1 - 4 * cold[3], cold


def test_dropping_the_rolling_noise_cools_the_spins_of_a_consistent_fluid(laws):
    """rolling_noise = false beside a sliding law with its noise (the per-mode negative control): stiff linear
    rolling friction (gamma_r = 50), solvent kept, 2-D: the spins cool by many errors."""
    sim = simulation(laws, ("coulomb_newton", "rolling_linear"), dim=2, rolling_noise=False, rolling_parameters={"gamma_r": 50.0})
    t_trans, e_trans, t_rot, e_rot = temperatures(sim, 10.0)
    assert t_rot < 1 - 10 * e_rot, (t_rot, e_rot)


@pytest.mark.parametrize("scheme", ["pairwise", "explicit"])
def test_the_rolling_noise_switch_keeps_the_sliding_noise(laws, scheme):
    """rolling_noise = false with a negligible rolling law (gamma_r = 1e-12) follows the sliding law alone with
    its noise (to 1e-9 over 200 steps), while contact_noise = false (the control) leaves it far behind."""
    faint = {"rolling_parameters": {"gamma_r": 1e-12}, "contact_scheme": scheme, "n": 27}
    alone = simulation(laws, ("coulomb_newton",), contact_scheme=scheme, n=27)
    switched = simulation(laws, ("coulomb_newton", "rolling_linear"), rolling_noise=False, **faint)
    silent = simulation(laws, ("coulomb_newton", "rolling_linear"), contact_noise=False, **faint)
    for sim in (alone, switched, silent):
        sim.threads = 1
        sim.advance(200)
    assert np.allclose(arrays(switched), arrays(alone), rtol=0, atol=1e-9)
    assert not np.allclose(arrays(silent), arrays(alone), rtol=0, atol=1e-3)
    with pytest.raises(ConfigError, match="^law.spinning_noise: drops the noise of no law"):
        config("coulomb_newton", spinning_noise=False)


def test_a_wrong_rolling_D_shows_in_the_explicit_kick(laws):
    """The rolling law's kernels with D doubled: the explicit kick heats the rotation by many errors (the
    right D keeps kT, above), while the pairwise step keeps kT for any D and shows it in its rejection rate."""
    right = laws["rolling_linear"]
    contact = right.module.contact_ito

    @numba.njit(CONTACT_KERNEL.signature)
    def doubled(u, w, r, mu, kT, params):
        ratio, amplitude = contact(u, w, r, mu, kT, params)
        return ratio, 2.0 * amplitude

    wrong = LawKernels(right.name, types.SimpleNamespace(**{**vars(right.module), "contact_ito": doubled}), right.path)
    hot = temperatures(simulation({"rolling_linear": wrong}, ("rolling_linear",), contact_scheme="explicit", dt=5e-4), 5.0)
    assert hot[2] > 1 + 6 * hot[3], hot  # measured: 1.084 +- 0.008
    kept = simulation({"rolling_linear": wrong}, ("rolling_linear",))
    assert at_kT(*temperatures(kept, 10.0))
    assert kept.tally.rejection_rate > 1e-3  # the linear law's right D is never rejected (an exact OU proposal)


@pytest.mark.parametrize("scheme", ["pairwise", "explicit"])
def test_all_modes_are_bit_identical_on_one_and_two_threads(laws, scheme):
    folder = laws["rolling_linear"].path.parent
    script = textwrap.dedent(f"""
        import hashlib, fricgen
        from tests.langevin.test_modes import arrays, simulation
        names = ("coulomb_newton", "rolling_linear", "spinning_linear")
        laws = {{name: fricgen.load_law(name, folder={str(folder)!r}) for name in names[1:]}}
        laws["coulomb_newton"] = fricgen.load_law("coulomb_newton")
        sim = simulation(laws, names, n=64, contact_scheme={scheme!r})
        sim.threads = fricgen.langevin.simulation.numba.get_num_threads()
        sim.advance(200)
        print(sim.threads, hashlib.sha256(arrays(sim).tobytes()).hexdigest())
    """)
    hashes = []
    for threads in ("1", "2"):
        env = {**os.environ, "NUMBA_NUM_THREADS": threads}
        done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=env, check=True)
        hashes.append(done.stdout.split())
    assert [h[0] for h in hashes] == ["1", "2"] and hashes[0][1] == hashes[1][1]


def test_a_rolling_law_leaves_the_sliding_path_and_the_translation_alone(laws):
    """A pure couple: with the rolling law only, and no solvent, the total momentum and the total angular
    momentum of the spins are conserved (to round-off), and the spins change."""
    sim = simulation(laws, ("rolling_linear",), dim=3, n=27, solvent=False)
    p = sim.particles
    before = (p.mass[:, None] * sim.state.velocity).sum(0), (p.inertia[:, None] * sim.state.omega).sum(0), sim.state.omega.copy()
    sim.threads = 1
    sim.advance(300)
    assert np.allclose((p.mass[:, None] * sim.state.velocity).sum(0), before[0], atol=1e-12)
    assert np.allclose((p.inertia[:, None] * sim.state.omega).sum(0), before[1], atol=1e-12)
    assert not np.allclose(sim.state.omega, before[2])


# --- the held-aside analytic check: an isolated pair's rolling velocity is an Ornstein–Uhlenbeck process ---


def isolated_pair(law, dim, dt, seed=3) -> Simulation:
    """Two spheres (R 0.5 and 0.3, I 0.1 and 0.036) in contact at r = 1.1 sigma_ik, no solvent, no sliding
    law; masses of 1e9 keep the normal fixed over the run (the WCA push moves them apart along it by ~1e-4
    sigma, within reach)."""
    radius, inertia = np.array([0.5, 0.3]), np.array([0.1, 0.036])
    particles = Particles(radius, np.full(2, 1e9), inertia, np.ones(2, dtype=bool))
    position = np.array([[5.0, 5.0, 5.0 if dim == 3 else 0.0], [5.0 + 1.1 * 0.8 * 0.6, 5.0 + 1.1 * 0.8 * 0.8, 5.0 if dim == 3 else 0.0]])
    omega = np.zeros((2, 3))
    omega[:, 2] = [1.0, -1.0]
    if dim == 3:
        omega[:, :2] = [[0.5, -1.0], [2.0, 0.3]]
    box = np.array([10.0, 10.0, 10.0 if dim == 3 else 0.0])
    state = State(position, np.zeros((2, 3)), omega, np.tile([1.0, 0, 0, 0], (2, 1)), box, dim)
    c = config(law.name, dt=dt, gamma=0.0, gamma_rot=0.0, seed=seed, parameters={"gamma_r": 20.0})
    return Simulation(c, particles, state, law)


def rolling_velocity(sim: Simulation) -> np.ndarray:
    """v_roll = R_eff (w_i - w_k) x n (3-D) or R_eff (w_iz - w_kz) (2-D), R_eff = R_i R_k / (R_i + R_k)."""
    s, r = sim.state, sim.particles.radius
    n = s.position[1] - s.position[0]
    n /= np.linalg.norm(n)
    difference = (s.omega[0] - s.omega[1]) * r[0] * r[1] / (r[0] + r[1])
    return np.cross(difference, n) if s.dim == 3 else difference[2:]


@pytest.mark.parametrize("dim", [2, 3])
def test_an_isolated_pairs_rolling_velocity_decays_at_the_derived_rate(laws, dim):
    """f = gamma_r u, D = gamma_r: <v_roll(t) . v_roll(0)> / <|v_roll|^2> = exp(-gamma_r mu_roll t) with
    mu_roll = R_eff^2 (1/I_i + 1/I_k) and <|v_roll|^2> = d_m mu_roll kT; the pairwise step is exact for
    this law at any dt (here gamma_r mu_roll dt = 0.27). The lag-one regression of the sampled series
    (an AR(1) process) has the standard error sqrt((1 - rho^2) / (d_m N)). Negative control: the rate of a
    wrong mobility (R in place of R_eff, the sliding mobility) is refused by many errors."""
    gamma, dt, samples = 20.0, 0.01, 5000
    reff = 0.5 * 0.3 / 0.8
    mu = reff**2 * (1 / 0.1 + 1 / 0.036)
    sim = isolated_pair(laws["rolling_linear"], dim, dt)
    sim.threads = 1
    sim.advance(500)  # forget the start (rate x time = 133)
    series = []
    for _ in range(samples):
        sim.advance(1)
        series.append(rolling_velocity(sim))
    x = np.array(series).reshape(samples, -1)
    components = 2 if dim == 3 else 1  # the rolling velocity is tangential
    rho = np.sum(x[1:] * x[:-1]) / np.sum(x[:-1] ** 2)
    expected = np.exp(-gamma * mu * dt)
    error = np.sqrt((1 - expected**2) / (components * samples))
    assert abs(rho - expected) < 4 * error, (rho, expected, error)
    variance = np.mean(np.sum(x**2, axis=1))
    spread = mu * np.sqrt(2 * components * (1 + expected**2) / (1 - expected**2) / samples)
    assert abs(variance - components * mu) < 4 * spread, (variance, components * mu, spread)
    sliding = 1 / 1e9 + 1 / 1e9 + 0.5**2 / 0.1 + 0.3**2 / 0.036
    for wrong in (0.5 * 0.3 * (1 / 0.1 + 1 / 0.036), sliding):
        assert abs(rho - np.exp(-gamma * wrong * dt)) > 20 * error


# --- the configuration: one law per mode, in the dimension it exists in ---


def test_the_mode_laws_are_checked_with_one_line_errors(laws):
    particles, dim = mixture(27), 3
    state = lattice_state(particles, dim, 0.3, seed=1)
    two = config("rolling_linear", rolling="rolling_linear")
    with pytest.raises(
        ConfigError, match=r"^law.rolling: a second law for the rolling mode \(law.name names rolling_linear\); one law per mode$"
    ):
        Simulation(two, particles, state, [laws["rolling_linear"], laws["rolling_linear"]])
    wrong = config("coulomb_newton", rolling="spinning_linear")
    with pytest.raises(ConfigError, match="^law.rolling: law spinning_linear acts on the spinning mode, not rolling"):
        Simulation(wrong, particles, state, [laws["coulomb_newton"], laws["spinning_linear"]])
    discs = mixture(16)
    flat = lattice_state(discs, 2, 0.5, seed=1)
    with pytest.raises(ConfigError, match="^law.spinning: law spinning_linear acts on spinning, which does not exist in 2-D"):
        Simulation(config("coulomb_newton", spinning="spinning_linear"), discs, flat, [laws["coulomb_newton"], laws["spinning_linear"]])
    with pytest.raises(ConfigError, match="^law.spinning_parameters.gamma_s: must be positive"):
        Simulation(
            config("coulomb_newton", spinning="spinning_linear", spinning_parameters={"gamma_s": -1.0}),
            particles,
            state,
            [laws["coulomb_newton"], laws["spinning_linear"]],
        )
    with pytest.raises(ConfigError, match="^law.rolling_parameters: sets parameters of no law"):
        config("coulomb_newton", rolling_parameters={"gamma_r": 1.0})


def test_a_checkpoint_of_all_modes_resumes_bit_identically(laws, tmp_path):
    names = ("coulomb_newton", "rolling_linear", "spinning_linear")
    whole, part = simulation(laws, names, n=27), simulation(laws, names, n=27)
    whole.threads = part.threads = 1
    whole.advance(100)
    part.advance(50)
    fricgen.langevin.save_checkpoint(tmp_path / "c.npz", part)
    again = fricgen.langevin.load_checkpoint(tmp_path / "c.npz", law=[laws[name] for name in names])
    again.threads = 1
    again.advance(50)
    assert np.array_equal(arrays(again), arrays(whole))
    other = dataclasses.replace(laws["spinning_linear"])
    object.__setattr__(other, "module", types.SimpleNamespace(**{**vars(laws["spinning_linear"].module), "SOURCE_HASH": "0" * 64}))
    with pytest.raises(ConfigError, match="the checkpoint ran .*spinning_linear.toml"):
        fricgen.langevin.load_checkpoint(tmp_path / "c.npz", law=[laws["coulomb_newton"], laws["rolling_linear"], other])


def test_a_run_file_names_one_law_per_mode(laws, tmp_path):
    """[law] rolling and spinning in a run file: resolved with the file's law folder, refused in one line
    for spinning in 2-D and for a law under another mode's key."""
    from fricgen.app.run.build import resolve_law
    from fricgen.app.run.config import load_config

    folder = laws["rolling_linear"].path.parent
    text = f"""[system]
dimension = 3
n = 64
packing_fraction = 0.3
[law]
name = "coulomb_newton"
rolling = "rolling_linear"
spinning = "spinning_linear"
folder = "{folder}"
[law.rolling_parameters]
gamma_r = 2.0
"""
    path = tmp_path / "run.toml"
    path.write_text(text)
    def resolve(path):
        config = load_config(path)
        return resolve_law(config.law, config.system.dimension)

    assert resolve(path).names == ["coulomb_newton", "rolling_linear", "spinning_linear"]
    path.write_text(text.replace("dimension = 3", "dimension = 2"))
    with pytest.raises(ConfigError, match="^law.spinning: law spinning_linear acts on spinning, which does not exist in 2-D"):
        resolve(path)
    swapped = text.replace('rolling = "rolling_linear"', 'rolling = "spinning_linear"').replace('spinning = "spinning_linear"\n', "")
    path.write_text(swapped.split("[law.rolling_parameters]")[0])
    with pytest.raises(ConfigError, match="^law.rolling: law spinning_linear acts on the spinning mode, not rolling"):
        resolve(path)
