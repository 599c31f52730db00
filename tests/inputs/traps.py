"""The trap of the input corpora: a case that gets past its checks into a simulation or a derivation
raises :class:`Started` instead of running it (a check that went missing fails its case at once)."""


class Started(AssertionError):
    """A case got as far as a simulation or a derivation."""


def stop(*args, **kwargs):
    raise Started("a corpus case started a simulation or a derivation")


def trap_simulations(monkeypatch) -> None:
    """Langevin runs, the run command's execution and the rods' simulation raise Started."""
    import fricgen.app.run.runner
    import fricgen.langevin.simulation
    import fricgen.rods.simulation

    monkeypatch.setattr(fricgen.langevin.simulation.Simulation, "run", stop)
    monkeypatch.setattr(fricgen.rods.simulation.RodSimulation, "__init__", stop)
    monkeypatch.setattr(fricgen.app.run.runner, "execute", stop)
