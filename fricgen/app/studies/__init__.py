"""Studies: what a user measures with the engines. ``demo`` and ``plots`` (the main job),
``thermostat_check`` (the statistical test of a law's thermostat), ``poiseuille`` and ``viscosity``
(slit flow and bulk viscosity), ``mips`` (phase separation of active discs), ``rods`` (BCD against the
exact theory). Importing the package registers the studies that analyse a run of their kind.
"""

from ..run.registry import STUDIES, Study
from . import mips, poiseuille

STUDIES["slit_flow"] = Study("poiseuille", poiseuille.summarize_run, poiseuille.describe_run)
STUDIES["active"] = Study("mips", mips.summarize_run, mips.describe_run)
