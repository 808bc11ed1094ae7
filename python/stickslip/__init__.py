"""stickslip: exact periodic motions, bifurcations, regime maps, chaos and
basins of friction oscillators, computed in process by the Rust library.

>>> import stickslip
>>> m = stickslip.Model("paper")
>>> motion = m.simulate(W=5, Q0=70)
>>> motion.structure
'P_{3_31 1_12 2_22 1_21 3_13 4_33}'
"""

from __future__ import annotations

from ._model import Model, Param, check, models
from ._results import Description, Equilibria, History, LawMotion, LawSweep, Motion, OrbitDiagram, Result, Sweep
from ._study import Basins, Curves, Lyapunov, Map
from .errors import (
    InadmissibleError,
    InputError,
    ModelError,
    NewtonError,
    ParamError,
    SeedError,
    SimulationError,
    StickslipError,
    StructureError,
    UnsettledError,
)

__all__ = [
    "LawMotion",
    "LawSweep",
    "Model",
    "Param",
    "models",
    "check",
    "Result",
    "Motion",
    "History",
    "Description",
    "Sweep",
    "Equilibria",
    "OrbitDiagram",
    "Map",
    "Curves",
    "Lyapunov",
    "Basins",
    "StickslipError",
    "ModelError",
    "ParamError",
    "StructureError",
    "InputError",
    "NewtonError",
    "InadmissibleError",
    "SeedError",
    "SimulationError",
    "UnsettledError",
]
