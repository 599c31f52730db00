"""Small systems shared by the engine tests."""

import dataclasses

import numpy as np

from fricgen.kernels import load_law_kernels
from fricgen.langevin import Active, Bulk, LangevinConfig, Law, Particles, Simulation, State, Thermostat, lattice_state

_LAW = {f.name for f in dataclasses.fields(Law)}
_THERMOSTAT = {f.name for f in dataclasses.fields(Thermostat)}


def config(law="coulomb_newton", active_force=0.0, bulk_force=(), **options):
    """A LangevinConfig from flat options (fields of Law, Thermostat and LangevinConfig)."""
    sections = {}
    for name, section, names in (("law", Law, _LAW), ("thermostat", Thermostat, _THERMOSTAT)):
        sections[name] = section(**{key: options.pop(key) for key in list(options) if key in names})
    sections["law"] = dataclasses.replace(sections["law"], name=law)
    return LangevinConfig(**sections, active=Active(active_force), bulk=Bulk(tuple(bulk_force)), **options)


def passive(law="coulomb_newton", dim=2, n=64, seed=3, law_kernels=None, **options):
    particles = Particles.spheres(n)
    state = lattice_state(particles, dim, 0.6 if dim == 2 else 0.3, seed=seed)
    return Simulation(config(law, seed=seed, **options), particles, state, law_kernels or load_law_kernels(law))


def collision(law, **options):
    """The two-sphere collision of the paper's SI (A): no thermostat, no noise, R = 1/2, m = 1."""
    particles = Particles.spheres(2)
    position = np.array([[10.0, 10.0, 10.0], [11.15, 10.4, 10.0]])
    velocity = np.array([[np.sqrt(3.0), 0.0, 0.0], [0.0, 0.0, 0.0]])
    omega = np.array([[0.0, 0.0, 2 * np.sqrt(30.0)], [0.0, 0.0, 0.0]])
    orientation = np.array([[1.0, 0, 0, 0], [1.0, 0, 0, 0]])
    state = State(position, velocity, omega, orientation, np.array([20.0, 20.0, 20.0]), 3)
    return Simulation(config(law, gamma=0.0, gamma_rot=0.0, contact_noise=False, **options), particles, state, load_law_kernels(law))


def arrays(simulation):
    s = simulation.state
    return np.concatenate([s.position.ravel(), s.velocity.ravel(), s.omega.ravel(), s.orientation.ravel()])
