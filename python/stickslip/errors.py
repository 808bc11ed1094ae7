"""The exceptions stickslip raises.

Every one is a :class:`StickslipError`. Bad input is also a :class:`ValueError`
(a model that does not exist or does not check, a parameter the model rejects,
a structure that is not the model's, a bad range or count); a computation that
gives no answer is a :class:`RuntimeError` (Newton did not converge, the
solution is not admissible, nothing to start Newton from, the simulation could
not go on). Messages are those of the command-line tool.
"""

from __future__ import annotations

from typing import Any, Optional


class StickslipError(Exception):
    """Base class of every stickslip error."""


class ModelError(StickslipError, ValueError):
    """No compiled-in model has this name, or a model file does not check
    (the message locates every error as ``file:line:col``)."""


class ParamError(StickslipError, ValueError):
    """A parameter the model does not have, or a value outside its bounds."""


class StructureError(StickslipError, ValueError):
    """A mapping structure that is not a structure of the model."""


class InputError(StickslipError, ValueError):
    """Another bad argument: a range, a count, a start state, a file."""


class NewtonError(StickslipError, RuntimeError):
    """Newton did not converge. ``result`` holds the report (kind
    ``not_converged``), when there is one."""

    def __init__(self, message: str, result: Optional[Any] = None) -> None:
        super().__init__(message)
        self.result = result


class InadmissibleError(StickslipError, RuntimeError):
    """Newton converged, but the solution violates an admissibility condition:
    it is not a motion. ``result`` holds it, with its ``violations``."""

    def __init__(self, message: str, result: Optional[Any] = None) -> None:
        super().__init__(message)
        self.result = result


class SeedError(StickslipError, RuntimeError):
    """No start for Newton: no simulated motion follows the structure (give
    ``guess=(Wt, x)``)."""


class UnsettledError(StickslipError, RuntimeError):
    """The simulation did not settle on a periodic motion, a certified NM or
    a permanent stick within the forcing periods given (or settled on a cycle
    longer than the search recognises): give more ``periods``, or ask
    ``lyapunov`` what is there."""


class SimulationError(StickslipError, RuntimeError):
    """The simulation could not go on (too many events, a bad start state)."""


__all__ = [
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
