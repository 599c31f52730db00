"""Small systems shared by the engine tests."""

import numpy as np

from fricgen.simulation import LangevinConfig, Simulation
from fricgen.system import Particles, State, lattice_state


def passive(law="coulomb_newton", dim=2, n=64, seed=3, **config):
    particles = Particles.spheres(n)
    state = lattice_state(particles, dim, 0.6 if dim == 2 else 0.3, seed=seed)
    return Simulation(LangevinConfig(law=law, seed=seed, **config), particles, state)


def collision(law, **config):
    """The two-sphere collision of the paper's SI (A): no thermostat, no noise, R = 1/2, m = 1."""
    particles = Particles.spheres(2)
    position = np.array([[10.0, 10.0, 10.0], [11.15, 10.4, 10.0]])
    velocity = np.array([[np.sqrt(3.0), 0.0, 0.0], [0.0, 0.0, 0.0]])
    omega = np.array([[0.0, 0.0, 2 * np.sqrt(30.0)], [0.0, 0.0, 0.0]])
    orientation = np.array([[1.0, 0, 0, 0], [1.0, 0, 0, 0]])
    state = State(position, velocity, omega, orientation, np.array([20.0, 20.0, 20.0]), 3)
    cfg = LangevinConfig(law=law, gamma=0.0, gamma_rot=0.0, contact_noise=False, **config)
    return Simulation(cfg, particles, state)


def arrays(simulation):
    s = simulation.state
    return np.concatenate([s.position.ravel(), s.velocity.ravel(), s.omega.ravel(), s.orientation.ravel()])
