"""What a run of any model settles on, named: the paper's kinds on the generic runtime.

`classify` runs the model from a start, measures the Lyapunov spectrum of the run
through its switches (`beltmdsm.oscillator.lyapunov.lyapunov`, with the error of its
average: half the difference of its two halves), and then asks, from the run's last
state, where the run provably lands (`beltmdsm.oscillator.basins.land`: steady sliding,
the recurring stick-end state of a stick-slip cycle, the recurring stroboscopic state of
a forced response, or the steady range of a slip cycle). What it lands on is shot
exactly (`beltmdsm.oscillator.responses.shoot_attractor`) and named by its own
stability, not by the spectrum:

* ``equilibrium``: stable steady sliding (its derived Hurwitz determinants);
* ``periodic``: a stable cycle (``cycle`` ``"stick_slip"`` or ``"slip"``, ``periods``
  1) or a stable forced response of ``periods`` excitation periods (``cycle``
  ``"forced"``: locked where ``periods > 1``);
* ``unstable``: the run sits on an invariant set whose eigenvalues or multipliers say it
  is unstable (steady sliding with a positive growth rate, or a cycle or response
  with a multiplier off the unit circle): a positive exponent there measures that set's
  instability and is not chaos (issue 36 item 2); the evidence names the set;
* ``quasi_periodic``: forced, no return of the stroboscopic state within the run, and
  the largest exponent zero within ``SIGNIFICANCE`` errors (the error below
  ``ZERO_FLOOR``) with the next one negative;
* ``chaotic``: the largest exponent positive beyond ``SIGNIFICANCE`` errors and
  ``ZERO_FLOOR``, on a run that lands on no set above;
* ``unclassified``: none of these; the evidence says which test failed.

The thresholds are those of the paper's classification
(`beltmdsm.attractors.classification`), which the tests keep equal.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import NoPeriodicResponse
from .basins import land
from .equilibria import steady_sliding
from .lyapunov import Spectrum, lyapunov
from .responses import shoot_attractor
from .system import System

__all__ = ["Settled", "classify", "SIGNIFICANCE", "ZERO_FLOOR", "ZERO_TOL"]

#: An exponent is nonzero where it is more than this many errors from zero (as the
#: paper's `beltmdsm.attractors.classification.SIGNIFICANCE`).
SIGNIFICANCE = 3.0
#: The largest error with which a zero exponent names a torus, and the least positive
#: exponent called chaos [1/s] (the paper's ``ZERO_FLOOR``).
ZERO_FLOOR = 1e-3
#: Added to ``SIGNIFICANCE`` errors where an exponent is judged zero [1/s] (``ZERO_TOL``).
ZERO_TOL = 5e-4
#: A run's last state within this of steady sliding (relative) sits on it.
_ON = 1e-6


@dataclass(repr=False)
class Settled:
    """What a run of a model settles on, and the evidence.

    Attributes
    ----------
    system : System
    kind : {"periodic", "quasi_periodic", "chaotic", "equilibrium", "unclassified", \
"unstable"}
        The paper's kinds (`beltmdsm.attractors.attractor.KINDS`).
    cycle : str
        ``"stick_slip"``, ``"slip"`` or ``"forced"`` for a periodic (or unstable
        periodic) set, else ``""``.
    periods : int or None
        Excitation periods of a forced response; 1 for a cycle; None otherwise.
    lyapunov, lyapunov_error : float
        The largest exponent and its error [1/s].
    exponents : ndarray (2n,)
        The spectrum (``-inf`` for a direction stick removes).
    evidence : str
        Why this kind, in one sentence.
    state : ndarray (2n,)
        A state on the set (the shooting state of a cycle or response), else the run's last.
    orbit : Equilibrium, Cycle, Response or None
        The set shot exactly, with its eigenvalues or multipliers.

    See Also
    --------
    classify : makes it.

    Examples
    --------
    A run started on unstable steady sliding sits on it (its exponent is the
    equilibrium's growth rate):

    >>> from beltmdsm.oscillator import System, steady_sliding
    >>> s = System("belt_1dof", friction="stribeck", Vb=1.5)
    >>> classify(s, steady_sliding(s).state, t_end=100.0)  # doctest: +ELLIPSIS
    Settled(System('belt_1dof', friction='stribeck', Vb=1.5); unstable, largest exponent +0.06...)
    """

    system: System
    kind: str
    cycle: str
    periods: int | None
    lyapunov: float
    lyapunov_error: float
    exponents: NDArray[np.float64]
    evidence: str
    state: NDArray[np.float64]
    orbit: object = None

    def __repr__(self) -> str:
        what = self.kind + (f" {self.cycle.replace('_', '-')}" if self.cycle else "")
        if self.cycle == "forced":
            what += f" ({self.periods}T)"
        return (
            f"Settled({self.system!r}; {what}, largest exponent {self.lyapunov:+.3g} +- "
            f"{self.lyapunov_error:.1g} 1/s)"
        )

    def as_dict(self) -> dict:
        """JSON-ready: the kind, the exponents (``-inf`` as None), the evidence (as the
        paper's `beltmdsm.attractors.attractor.Attractor.as_dict`; the model is the
        caller's to name)."""
        return {
            "kind": self.kind,
            "cycle": self.cycle,
            "periods": self.periods,
            "lyapunov": self.lyapunov,
            "lyapunov_error": self.lyapunov_error,
            "exponents": [float(v) if math.isfinite(v) else None for v in self.exponents],
            "evidence": self.evidence,
            "state": [float(v) for v in self.state],
        }


def _settled(spec: Spectrum, kind, evidence, cycle="", periods=None, state=None, orbit=None):
    return Settled(
        spec.system, kind, cycle, periods, spec.largest, float(spec.error[0]),
        spec.exponents, evidence, spec.state if state is None else np.asarray(state), orbit,
    )  # fmt: skip


def _on_sliding(spec: Spectrum) -> Settled | None:
    """``unstable`` where the run ends on steady sliding that is unstable."""
    system = spec.system
    if system.excitation_period() is not None:
        return None
    eq = steady_sliding(system)
    scale = 1.0 + float(np.abs(eq.state).max())
    off = float(np.abs(spec.state - eq.state).max())
    if eq.stable or off > _ON * scale:
        return None
    return _settled(
        spec,
        "unstable",
        f"the run sits on steady sliding ({off:.1e} off it at its end), which is unstable "
        f"(growth rate {eq.growth_rate:+.4g} 1/s; largest exponent {spec.largest:+.4g} "
        "1/s): its instability, not chaos; a start off it leaves it",
        state=eq.state,
        orbit=eq,
    )


def _landed(spec: Spectrum, t_end: float, limit: int) -> Settled | None:
    """What the run from its last state lands on, shot and named by its stability."""
    a = land(spec.system, spec.state, t_end=t_end, max_periods=limit)
    if a.kind == "unresolved":
        return None
    try:
        orbit = shoot_attractor(spec.system, a)
    except NoPeriodicResponse as err:
        return _settled(
            spec,
            "unclassified",
            f"the run lands on a {a.kind.replace('_', '-')} set but its shooting fails: {err}",
        )
    if a.kind == "steady_sliding":
        return _settled(
            spec,
            "equilibrium",
            f"the run lands on steady sliding, stable (growth rate {orbit.growth_rate:+.4g} "
            f"1/s; largest exponent {spec.largest:+.3g} 1/s)",
            state=orbit.state,
            orbit=orbit,
        )
    forced = a.kind == "periodic"
    cycle = "forced" if forced else orbit.kind
    periods = orbit.periods if forced else 1
    largest = float(np.abs(orbit.multipliers).max())
    if forced:
        what = f"the forced response of {periods} excitation period(s)"
    else:
        what = f"a {orbit.kind.replace('_', '-')} cycle of period {orbit.period:.8g} s"
    if not orbit.stable:
        return _settled(
            spec,
            "unstable",
            f"the run sits on {what}, which is unstable (largest |multiplier| {largest:.6g}): "
            "a positive exponent there is its instability, not chaos",
            cycle=cycle,
            periods=periods,
            state=orbit.state,
            orbit=orbit,
        )
    return _settled(
        spec,
        "periodic",
        f"the run lands on {what}, stable (largest |multiplier| {largest:.6g}, shooting "
        f"residual {orbit.residual:.1e})",
        cycle=cycle,
        periods=periods,
        state=orbit.state,
        orbit=orbit,
    )


def classify(
    system: System,
    y0: ArrayLike | None = None,
    *,
    t_end: float = 1000.0,
    t_transient: float | None = None,
    limit: int = 8,
) -> Settled:
    """What the run of ``system`` from ``y0`` settles on, named (module docstring).

    Parameters
    ----------
    system : System
    y0 : array_like (2n,), optional
        The start; rest by default (as `beltmdsm.oscillator.simulate`).
    t_end, t_transient : float
        The run and the part of it before the exponents are averaged
        (`beltmdsm.oscillator.lyapunov.lyapunov`, whose checks apply); the landing from
        the run's last state runs at most ``t_end`` again. Where the model is forced,
        both are cut down to whole excitation periods (the landing starts at phase 0),
        ``t_end`` at least two.
    limit : int
        The most excitation periods (or sticks per period) looked for.

    Returns
    -------
    Settled

    See Also
    --------
    beltmdsm.attractors.classification.classify : the paper's, which calls this for
        another model.

    Examples
    --------
    >>> from beltmdsm.oscillator import System, steady_sliding
    >>> s = System("belt_1dof", friction="stribeck", Vb=1.5)
    >>> a = classify(s, t_end=200.0)
    >>> a.kind, a.cycle, round(a.orbit.period, 6)
    ('periodic', 'stick_slip', 6.654342)
    >>> classify(s, steady_sliding(s).state, t_end=100.0).kind  # on unstable sliding
    'unstable'
    """
    T = system.excitation_period()
    if T is not None:  # whole periods: the run ends at phase 0, where the landing starts
        if not t_end >= 2 * T:
            raise ValueError(f"t_end={t_end!r}: shorter than two excitation periods ({T:g} s)")
        t_end = T * math.floor(t_end / T)
        if t_transient is not None and not 0 <= t_transient < t_end:
            raise ValueError(f"t_transient={t_transient!r}: not in [0, t_end = {t_end:g})")
        t_transient = T * math.floor((0.3 * t_end if t_transient is None else t_transient) / T)
    spec = lyapunov(system, y0, t_end=t_end, t_transient=t_transient)
    found = _on_sliding(spec) or _landed(spec, t_end, limit)
    if found is not None:
        return found
    lam, err = spec.largest, float(spec.error[0])
    bound = SIGNIFICANCE * err + ZERO_TOL
    if spec.status != "done":
        return _settled(spec, "unclassified", f"the run stopped: {spec.status}")
    if lam > max(bound, ZERO_FLOOR):
        return _settled(
            spec,
            "chaotic",
            f"the largest Lyapunov exponent {lam:+.4g} 1/s is positive beyond "
            f"{SIGNIFICANCE:g} times its error {err:.1g} and {ZERO_FLOOR:g} 1/s, on a run "
            "that lands on no equilibrium, cycle or periodic response",
        )
    second = float(spec.exponents[1])
    forced = system.excitation_period() is not None
    if forced and abs(lam) <= bound and err <= ZERO_FLOOR and second < -bound:
        return _settled(
            spec,
            "quasi_periodic",
            f"no return of the stroboscopic state within {limit} periods, the largest "
            f"exponent {lam:+.2g} 1/s zero within {bound:.1g} and the next {second:+.3g} "
            "1/s negative: an attracting torus",
        )
    return _settled(
        spec,
        "unclassified",
        f"the run lands on no equilibrium, cycle or response within {t_end:g} s; largest "
        f"exponent {lam:+.3g} +- {err:.1g} 1/s, next {second:+.3g} 1/s",
    )
