"""The settings of the continuation driver: one frozen, validated dataclass.

As BifurcationKit's ``ContinuationPar``: the step bounds of the pseudo-arclength walk,
the corrector's iterations and the tolerances, checked once where they enter
(`ContinuationSettings.__post_init__`); the driver (`beltmdsm.continuation.driver`)
reads them and re-checks nothing. Each problem (`beltmdsm.continuation.problem`) has
its defaults (``Problem.default_settings``): the forced period map's are
`FORCED_SETTINGS`, the autonomous cycle's `CYCLE_SETTINGS` (a shorter longest step and
a finer bracket: a cycle's Jacobian bends faster in the period).
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, replace

__all__ = ["ContinuationSettings", "FORCED_SETTINGS", "CYCLE_SETTINGS", "as_settings"]


@dataclass(frozen=True)
class ContinuationSettings:
    """Step bounds, corrector iterations and tolerances of the continuation driver.

    Parameters
    ----------
    step_first : float
        The first arclength step (scaled coordinates) and the one after a stick onset.
    step_min : float
        A step halved below this ends the branch (``failed``, a tangency or a grazing).
    step_max : float
        Steps grow by 1.5 after easy corrections up to this.
    corrector_iter : int
        Newton iterations of the corrector.
    easy : int
        A correction in at most this many iterations lets the step grow.
    s_tol : float
        A special point's regula falsi stops at brackets below this (scaled arclength).
    max_points : int
        Accepted points per walk at most (the walk then ends ``failed``).
    crawl_step : float
        Steps below this count towards a crawl ...
    crawl_limit : int
        ... and this many in a row make the driver try to locate the end it approaches
        (``Problem.near_end``).

    Raises
    ------
    ValueError
        Naming the field: a step bound that is not finite and positive, bounds out of
        order (``step_min <= step_first <= step_max``), a count below 1.

    See Also
    --------
    beltmdsm.continuation.driver.walk : the driver that reads them.
    beltmdsm.continuation.branch.branch : takes ``settings=``.

    Examples
    --------
    >>> from beltmdsm.continuation.settings import ContinuationSettings, FORCED_SETTINGS
    >>> FORCED_SETTINGS.step_max, FORCED_SETTINGS.corrector_iter
    (0.25, 12)
    >>> ContinuationSettings(step_max=0.1).step_max
    0.1
    >>> ContinuationSettings(step_min=1.0)
    Traceback (most recent call last):
    ...
    ValueError: step bounds must satisfy step_min <= step_first <= step_max; got 1.0, 0.02, 0.25
    """

    step_first: float = 0.02
    step_min: float = 1e-7
    step_max: float = 0.25
    corrector_iter: int = 12
    easy: int = 4
    s_tol: float = 1e-12
    max_points: int = 2000
    crawl_step: float = 1e-4
    crawl_limit: int = 8

    def __post_init__(self) -> None:
        for name in ("step_first", "step_min", "step_max", "s_tol", "crawl_step"):
            v = getattr(self, name)
            ok = isinstance(v, numbers.Real) and not isinstance(v, bool)
            if not (ok and math.isfinite(v) and v > 0):
                raise ValueError(f"{name} must be a finite positive number; got {v!r}")
        for name in ("corrector_iter", "easy", "max_points", "crawl_limit"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, numbers.Integral) or v < 1:
                raise ValueError(f"{name} must be an integer >= 1; got {v!r}")
        if not self.step_min <= self.step_first <= self.step_max:
            raise ValueError(
                "step bounds must satisfy step_min <= step_first <= step_max; got "
                f"{self.step_min!r}, {self.step_first!r}, {self.step_max!r}"
            )


#: The forced ``k``-fold period map's defaults.
FORCED_SETTINGS = ContinuationSettings()
#: The autonomous cycle's defaults: a shorter longest step, a finer bracket.
CYCLE_SETTINGS = replace(FORCED_SETTINGS, step_max=0.2, s_tol=1e-13)


def as_settings(
    settings: ContinuationSettings | None, default: ContinuationSettings
) -> ContinuationSettings:
    """``settings``, or ``default`` where None; anything else is refused in one line.

    Parameters
    ----------
    settings : ContinuationSettings or None
        What the caller passed as ``settings=``.
    default : ContinuationSettings
        The problem's defaults.

    Returns
    -------
    ContinuationSettings

    Raises
    ------
    TypeError
        Where ``settings`` is neither.

    See Also
    --------
    beltmdsm.continuation.settings.ContinuationSettings : the dataclass.

    Examples
    --------
    >>> as_settings(None, CYCLE_SETTINGS).step_max
    0.2
    >>> as_settings({"step_max": 0.1}, CYCLE_SETTINGS)
    Traceback (most recent call last):
    ...
    TypeError: settings must be a ContinuationSettings or None; got {'step_max': 0.1}
    """
    if settings is None:
        return default
    if not isinstance(settings, ContinuationSettings):
        raise TypeError(f"settings must be a ContinuationSettings or None; got {settings!r}")
    return settings
