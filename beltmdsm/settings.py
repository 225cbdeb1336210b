"""How a run is computed: `SolverSettings`, the integrators' options and limits.

The settings are checked once, when they are built, and normalised (every number a
float), so that equal settings key the sweep cache equally whether they came from
the command line or from Python.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from typing import Literal

from .model import Backend, is_real

__all__ = [
    "SolverSettings",
    "SOLVERS",
    "METHODS",
    "CONTACT_LOSS",
    "MAX_SAMPLES",
    "MAX_POINTS",
    "DEFAULT_T_END",
]

#: The integrators: `beltmdsm.integrate.events` and `beltmdsm.integrate.superposition`.
SOLVERS = ("events", "superposition")
#: The integration methods of the integrators (`beltmdsm.integrate._dop853`), by name
#: (the name keys the sweep cache).
METHODS = ("DOP853",)
#: What a run does on loss of contact: go on in flight, or stop.
CONTACT_LOSS = ("continue", "stop")
#: Most samples in a run's time series (``t_end / dt``): each costs 7 floats in the
#: returned arrays, so this caps them near 0.6 GB, and an absurd request fails before
#: anything is allocated.
MAX_SAMPLES = 10**7
#: Most points of one sweep (`beltmdsm.studies.sweep`). A sweep of 10^6 runs of a second
#: each is eleven days on one core; a larger one is a mistake (a step of 1e-15), refused
#: before anything is allocated.
MAX_POINTS = 10**6
DEFAULT_T_END = 1000.0


@dataclass(frozen=True)
class SolverSettings:
    """How a run is computed; part of the cache key of a sweep.

    ``solver``: "events" (the default; `beltmdsm.integrate.events`, the compiled
    DOP853 integrator on each mode: the general one, and the faster) or
    "superposition" (`beltmdsm.integrate.superposition`: the normal equation once, the
    tangential one by superposition; it falls back to "events" where it does not
    apply). ``method``: the Runge-Kutta method ("DOP853", the only one). ``dt``:
    sampling step of the returned time series [s]. ``t_discard``: start of the steady
    window [s]; ``None`` means 30 % of ``t_end``. ``backend``: "numba" (compiled),
    "python" or None (numba if installed).

    Raises
    ------
    ValueError
        Naming the field, for a bad value or settings that do not fit together.
    """

    solver: Literal["events", "superposition"] = "events"
    method: Literal["DOP853"] = "DOP853"
    rtol: float = 1e-10
    atol: float = 1e-10
    t_end: float = DEFAULT_T_END
    t_discard: float | None = None
    dt: float = 0.02
    on_contact_loss: Literal["continue", "stop"] = "continue"
    backend: Backend | None = None

    def __post_init__(self) -> None:
        for name, choices in (
            ("solver", SOLVERS),
            ("method", METHODS),
            ("on_contact_loss", CONTACT_LOSS),
            ("backend", (None, "numba", "python")),
        ):
            if getattr(self, name) not in choices:
                raise ValueError(
                    f"{name} must be one of {', '.join(map(repr, choices))}; "
                    f"got {getattr(self, name)!r}"
                )
        for name in ("rtol", "atol", "t_end", "dt"):
            value = getattr(self, name)
            if not (is_real(value) and math.isfinite(value) and value > 0):
                raise ValueError(f"{name} must be a finite number > 0; got {value!r}")
            object.__setattr__(self, name, float(value))
        if self.t_discard is not None:
            if not (is_real(self.t_discard) and math.isfinite(self.t_discard)):
                raise ValueError(
                    f"t_discard must be None or a finite number; got {self.t_discard!r}"
                )
            object.__setattr__(self, "t_discard", float(self.t_discard))
        if self.t_end / self.dt > MAX_SAMPLES:
            raise ValueError(
                f"t_end / dt = {self.t_end / self.dt:.3g} samples is more than "
                f"MAX_SAMPLES = {MAX_SAMPLES:.0e} (beltmdsm/settings.py); "
                "shorten t_end or sample with a larger dt"
            )
        if not 0 <= self.window_start < self.t_end - 20 * self.dt:
            raise ValueError(
                f"t_discard={self.t_discard!r} must be >= 0 and leave a steady "
                f"window before t_end={self.t_end!r}"
            )

    @property
    def window_start(self) -> float:
        return 0.3 * self.t_end if self.t_discard is None else float(self.t_discard)

    @classmethod
    def names(cls) -> tuple[str, ...]:
        """The field names (keywords that `beltmdsm.simulate` passes to the settings)."""
        return tuple(f.name for f in fields(cls))
