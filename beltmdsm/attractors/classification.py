"""What a run settles on, named: equilibrium, periodic, quasi-periodic or chaotic.

`classify` runs the model from a state, measures the Lyapunov spectrum of the run
(`beltmdsm.attractors.lyapunov`, through the switches) and reads the attractor's kind
from the spectrum and the stroboscopic samples (the state at the excitation's phase 0,
one per excitation period):

* ``periodic``: the last samples repeat after ``k`` periods to `RETURN_TOL` (searched up
  to a third of the samples, far beyond the 12 of `beltmdsm.periodic.locked.LOCK_LIMIT`),
  and Newton's method on the ``k``-fold period map from the last sample converges
  (`beltmdsm.periodic.shooting.periodic_response`): ``periods`` is ``k``, minimal. Its
  rotation number about the samples' centre is then a fraction ``p / k``.
* ``quasi_periodic``: no return, the samples on a closed curve (an invariant circle of
  the stroboscopic map, a torus of the flow: `beltmdsm.periodic.locked.NotLocked`) and
  the largest exponent zero within its error, that error below `ZERO_FLOOR` (the slow
  contraction towards a long lock, -0.015 1/s at the base set's 59T lock, must be told
  from zero; a short run cannot): the motion along the curve neither
  grows nor decays. Its rotation number is a weighted Birkhoff average of the angle
  turned per period (Das, Sander and Yorke 2016: the weights ``exp(-1/(t (1 - t)))``
  make it converge faster than any power of the samples on a smooth circle), its
  accuracy the difference between the averages over all samples and over the first
  half. The second exponent says whether the curve attracts.
* ``chaotic``: the largest exponent positive beyond `SIGNIFICANCE` times its error and
  beyond `ZERO_FLOOR`, on a run that is neither on an equilibrium nor on a periodic
  response (``unstable`` below).
* ``equilibrium``: without excitation, the samples standing still and every exponent
  negative (steady sliding).
* ``unstable``: the run begins its averaging window on (or within `NEAR` of) an
  invariant set that is unstable: steady sliding whose eigenvalues have a positive
  real part, or a ``k``-periodic response (the first samples return, Newton's method
  converges from them) whose Floquet multipliers leave the unit circle
  (`unstable_set`). A positive exponent there is that set's instability, not chaos;
  ``periods`` is ``k`` (None for steady sliding) and the evidence names the set, its
  growth rate against the exponent, and how long the run would take to leave it.
  A careful researcher's start is off such a set: `lyapunov` and this function by
  default start as `beltmdsm.simulation.simulate` does (moved off unstable steady
  sliding along its unstable direction, with the transient the run takes to leave
  it where ``t_end`` allows); an explicit ``y0`` on the set is honoured and named.
* ``unclassified``: none of these holds; the evidence says which test failed (a
  negative exponent without a return: a lock longer than the run can show; a zero
  exponent off a closed curve).

Without excitation the samples are taken every base period
(`beltmdsm.attractors.lyapunov.chunk_length`) and there is no phase: a self-excited cycle
has a zero largest exponent (the direction along the flow) and is ``periodic`` where it
is found as a cycle (``periods`` 1).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from .. import state_names
from .._calling import public
from ..arguments import number, state
from ..errors import NoPeriodicResponse, StepTooSmall
from ..excitation import excitation_period, initial_state
from ..model import Backend, Model, as_model
from ..periodic.floquet import Floquet
from ..periodic.locked import NotLocked, stroboscope
from ..periodic.shooting import periodic_response
from .attractor import KINDS, Attractor
from .lyapunov import advance, check_length, lyapunov
from .rotation import _CANDIDATES, NEAR, RETURN_TOL, _angles, _returns, rotation_number
from .unstable_set import _unstable_response, unstable_set

__all__ = [
    "Attractor",
    "KINDS",
    "classify",
    "periodic_attractor",
    "rotation_number",
    "unstable_set",
    "NEAR",
    "RETURN_TOL",
    "SIGNIFICANCE",
    "ZERO_FLOOR",
    "ZERO_TOL",
]

#: An exponent is nonzero where it is more than this many errors from zero.
SIGNIFICANCE = 3.0
#: The largest error with which a zero exponent names a torus, and the least positive
#: exponent called chaos [1/s]: the long locks found here contract at 0.003-0.05 1/s
#: (omega1 = 0.3, Vb = 9.25: -0.0029 +- 0.002 over 6000 s, no return in 884 periods,
#: its neighbours 93T and 40T locks), and a run that cannot tell that from zero says so.
ZERO_FLOOR = 1e-3
#: Added to ``SIGNIFICANCE`` errors where an exponent is judged zero [1/s]: a torus's
#: exponent converges like 1/t, which the block spread does not see.
ZERO_TOL = 5e-4
#: The absolute accuracy of a Floquet multiplier (the two period-map engines agree to
#: this: beltmdsm/periodic/general_map.py), the error of `periodic_attractor`'s exponent.
_MULTIPLIER_TOL = 1e-9


@public(models=True)
def classify(
    model: Model | Mapping[str, Any] | None = None,
    *,
    y0: ArrayLike | None = None,
    t_end: float = 2000.0,
    t_transient: float | None = None,
    backend: Backend | None = None,
) -> Attractor:
    """The attractor the run from ``y0`` settles on, named (module docstring).

    Parameters
    ----------
    model : Model, optional
        Or the keywords it is built from.
    y0 : array_like (4,), optional
        The start; default the unforced equilibrium at rest.
    t_end, t_transient : float
        The run and the part of it before the spectrum and the samples are taken (as
        `beltmdsm.attractors.lyapunov.lyapunov`, whose checks apply).
    backend : {"python", "numba", None}

    Returns
    -------
    Attractor
        For another registered model (``Model(model="belt_1dof")``) a
        `beltmdsm.oscillator.classification.Settled`: the same kinds, from the generic
        runtime's spectrum and where its run lands (its default start: rest;
        ``backend`` is refused).

    See Also
    --------
    beltmdsm.attractors.lyapunov.lyapunov : the spectrum.
    beltmdsm.periodic.locked.NotLocked : the closed-curve test.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> classify(Model(Vb=9.0), t_end=300.0).kind
    'periodic'
    """
    model = as_model(model)
    if model.model != "paper":  # another registered model: the generic runtime
        from ..oscillator import api

        t_end = number("t_end", t_end, above=0)
        return api.classify(model, y0, t_end, t_transient, backend=backend)
    spec = lyapunov(model, y0=y0, t_end=t_end, t_transient=t_transient, backend=backend)
    try:
        excitation_period(model)
    except ValueError:
        return _unforced(model, spec)
    return _forced(model, spec, backend)


#: The shortest run of `periodic_attractor`, in excitation periods: its samples start
#: after 30 % of the run, one a period, and the run's settings need 20 of them
#: (`beltmdsm.settings.SolverSettings`).
MIN_PERIODS = 22


def run_length(t_end: Any, period: float) -> float:
    """``t_end`` checked as the length of a `periodic_attractor` run of a model of
    excitation period ``period``: at least `MIN_PERIODS` of them (a ValueError naming
    ``t_end`` otherwise, before anything runs)."""
    t_end = number("t_end", t_end, above=0)
    if not t_end >= MIN_PERIODS * period:
        raise ValueError(
            f"t_end must be at least {MIN_PERIODS} excitation periods "
            f"({MIN_PERIODS * period:.4g} s); got {t_end:g}"
        )
    return t_end


@public()
def periodic_attractor(
    model: Model | Mapping[str, Any] | None = None,
    *,
    y0: ArrayLike | None = None,
    t_end: float = 2000.0,
    backend: Backend | None = None,
) -> Attractor:
    """The stable periodic attractor the run from ``y0`` settles on, without a Lyapunov run.

    The fast path of `classify` where the run locks: a plain run (no variational
    equations, a fifth of `beltmdsm.attractors.lyapunov.lyapunov`'s cost), its
    stroboscopic samples after the first 30 % searched for returns as `classify` does,
    Newton's method on the ``k``-fold map from the last, and the exponents
    ``ln |mu_i| / (k T)`` of the response's Floquet multipliers: exactly what the
    Lyapunov spectrum of a run on it converges to (tests/beltmdsm/attractors/test_lyapunov.py),
    with the multipliers' accuracy instead of an average's error.

    Parameters
    ----------
    model : Model, optional
        Or the keywords it is built from; it must have a periodic excitation.
    y0 : array_like (4,), optional
        The start; default the unforced equilibrium at rest.
    t_end : float
        The run [s].
    backend : {"python", "numba", None}

    Returns
    -------
    Attractor
        Of kind ``periodic``.

    Raises
    ------
    NoPeriodicResponse
        Where the samples do not return, Newton's method does not converge from them or
        the response is not stable: `classify` then names the attractor.
    ValueError
        For a bad ``t_end`` or ``y0``, or no excitation.

    See Also
    --------
    beltmdsm.attractors.classification.classify : every kind, from the Lyapunov spectrum.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> a = periodic_attractor(Model(Vb=3.88), t_end=300.0)
    >>> a.kind, a.periods, round(a.lyapunov, 4)
    ('periodic', 4, -0.0951)
    """
    model = as_model(model)
    T = excitation_period(model)
    t_end = run_length(t_end, T)
    check_length(model, t_end)
    names = state_names.names(model)
    y = initial_state(model) if y0 is None else state("y0", y0, (len(names),), ", ".join(names))
    first = T * np.ceil(0.3 * t_end / T)
    times = first + T * np.arange(int((t_end - first) / T + 1e-9) + 1)
    try:  # in pieces: only the samples are kept
        _, samples = advance(model, y, 0.0, float(times[-1]), backend=backend, times=times)
    except StepTooSmall as err:
        raise NoPeriodicResponse(f"periodic_attractor: {err}") from None
    for k in _returns(samples, RETURN_TOL)[:_CANDIDATES]:
        try:
            resp = periodic_response(
                model, periods=k, guess=samples[-1], forward=0, backend=backend
            )
        except NoPeriodicResponse:
            continue
        f = Floquet.of(resp)
        if not f.stable:  # unstable, or grazing (stable None): classify decides
            raise NoPeriodicResponse(
                f"the {k}T response the run returns to is not stable by its Floquet "
                f"multipliers (stable: {f.stable})"
            )
        mu = np.sort(np.abs(f.multipliers))[::-1]
        with np.errstate(divide="ignore"):
            exponents = np.log(mu) / f.period
        # below the multipliers' error floor an exponent is no number: only its bound
        bound = math.log(f.floor) / f.period
        exponents = np.where((mu < f.floor) & (mu > 0), np.nan, exponents)
        low = int(np.sum(np.isnan(exponents)))
        floor_note = (
            f"; {low} multiplier(s) below the computation's error floor {f.floor:.1e} "
            f"(beltmdsm/periodic/floquet.py): their exponents are below {bound:.4g} 1/s "
            "(NaN), not numbers"
            if low
            else ""
        )
        turns = np.angle(np.exp(1j * np.diff(_angles(samples[-(k + 1) :]))))
        p = int(round(float(np.sum(turns)) / (2 * np.pi)))
        return Attractor(
            "periodic",
            k,
            p / k,
            0.0,
            float(exponents[0]),
            # d ln|mu| = d|mu| / |mu|: the multiplier's error (its floor, the engines'
            # agreement) or Newton's residual
            max(resp.residual, _MULTIPLIER_TOL, f.floor) / (max(mu[0], 1e-300) * f.period),
            exponents,
            f"the samples return after {k} excitation periods, Newton's method on the "
            f"{k}-fold period map converges from them (residual {resp.residual:.1e}) and "
            f"the Floquet multipliers are inside the unit circle (largest {mu[0]:.6g}): the "
            "exponents are ln|mu| / (k T)" + floor_note,
            resp.state0,
            samples,
            bound if low else None,
        )
    raise NoPeriodicResponse(
        f"the run's samples do not return to {RETURN_TOL:g} within {len(samples) // 3} "
        "periods onto a periodic response"
    )


def _attractor(kind, spec, evidence, periods=None, rotation=None, accuracy=None, state=None):
    return Attractor(
        kind,
        periods,
        rotation,
        accuracy,
        spec.largest,
        float(spec.error[0]),
        spec.exponents,
        evidence,
        spec.state if state is None else np.asarray(state, dtype=float),
        spec.samples,
    )


def _forced(model, spec, backend):
    lam, err = spec.largest, float(spec.error[0])
    bound = SIGNIFICANCE * err + ZERO_TOL
    tried = []
    for k in _returns(spec.samples, RETURN_TOL)[:_CANDIDATES]:
        try:
            resp = periodic_response(
                model, periods=k, guess=spec.samples[-1], forward=0, backend=backend
            )
        except NoPeriodicResponse:
            tried.append(str(k))
            continue
        unstable = _unstable_response(resp, spec, "ends its averaging window on")
        if unstable is not None:
            evidence, k, on = unstable
            return _attractor("unstable", spec, evidence, periods=k, state=on)
        turns = np.angle(np.exp(1j * np.diff(_angles(spec.samples[-(k + 1) :]))))
        p = int(round(float(np.sum(turns)) / (2 * np.pi)))
        return _attractor(
            "periodic",
            spec,
            f"the samples return after {k} excitation periods and Newton's method on the "
            f"{k}-fold period map converges from them (residual {resp.residual:.1e})",
            periods=k,
            rotation=p / k,
            accuracy=0.0,
            state=resp.state0,
        )
    note = (
        f"; the close returns after {', '.join(tried)} periods are no periodic response "
        "(Newton's method does not converge from them)"
        if tried
        else ""
    )
    if lam > max(bound, ZERO_FLOOR):
        unstable = unstable_set(model, spec, backend)
        if unstable is not None:
            evidence, k, on = unstable
            return _attractor("unstable", spec, evidence + note, periods=k, state=on)
        return _attractor(
            "chaotic",
            spec,
            f"the largest Lyapunov exponent {lam:+.4g} 1/s is positive beyond "
            f"{SIGNIFICANCE:g} times its error {err:.1g} and {ZERO_FLOOR:g} 1/s, on a run "
            "that begins its window on no equilibrium or periodic response" + note,
        )
    notlocked = NotLocked.of(stroboscope(spec.samples, "run", limit=1))
    precise = err <= ZERO_FLOOR
    if abs(lam) <= bound and precise and notlocked.closed_curve:
        rot, acc = rotation_number(spec.samples)
        attracts = "attracts" if spec.exponents[1] < 0 else "does not attract"
        return _attractor(
            "quasi_periodic",
            spec,
            f"no return within {spec.samples.shape[0] // 3} periods, the samples on a "
            f"closed curve (correlation dimension {notlocked.dimension:.2f}), the largest "
            f"exponent {lam:+.2g} 1/s zero within {bound:.1g}; the curve {attracts} "
            f"(second exponent {spec.exponents[1]:+.3g} 1/s)" + note,
            rotation=rot,
            accuracy=acc,
        )
    if lam < -bound:
        why = (
            f"the largest exponent {lam:+.3g} 1/s is negative (a periodic attractor) but "
            f"the samples do not return within {spec.samples.shape[0] // 3} periods to "
            f"{RETURN_TOL:g}: a lock longer than the run shows, or a transient; run longer"
        )
    elif not precise:
        why = (
            f"the largest exponent {lam:+.3g} +- {err:.1g} 1/s: its error is above "
            f"{ZERO_FLOOR:g} 1/s, too large to tell a torus (zero) from a slow contraction "
            f"to a lock longer than the run shows; run longer"
        )
    else:
        why = (
            f"the largest exponent {lam:+.2g} 1/s is zero within {bound:.1g} but the "
            f"samples do not lie on one closed curve (correlation dimension "
            f"{notlocked.dimension:.2f})"
        )
    return _attractor("unclassified", spec, why + note)


def _unforced(model, spec):
    lam, err = spec.largest, float(spec.error[0])
    bound = SIGNIFICANCE * err + ZERO_TOL
    y = spec.samples
    scale = 1.0 + float(np.max(np.abs(y)))
    still = float(np.max(np.ptp(y, axis=0))) <= RETURN_TOL * scale
    if still and lam < -bound:
        return _attractor(
            "equilibrium",
            spec,
            f"the state stands still (to {RETURN_TOL:g}) and every exponent is negative "
            f"(largest {lam:+.3g} 1/s): steady sliding, stable",
        )
    if lam >= -bound:  # not stable: is the run on (or leaving) unstable sliding?
        unstable = unstable_set(model, spec)
        if unstable is not None:
            evidence, _, on = unstable
            return _attractor("unstable", spec, evidence, state=on)
    if lam > max(bound, ZERO_FLOOR):
        return _attractor(
            "chaotic",
            spec,
            f"the largest Lyapunov exponent {lam:+.4g} 1/s is positive beyond "
            f"{SIGNIFICANCE:g} times its error {err:.1g} and {ZERO_FLOOR:g} 1/s, on a run "
            "that does not begin its window near steady sliding",
        )
    if abs(lam) <= bound and not still and spec.exponents[1] < -bound:
        return _attractor(
            "periodic",
            spec,
            f"a self-excited cycle: the largest exponent {lam:+.2g} 1/s is zero within "
            f"{bound:.1g} (the direction along the flow) and the next "
            f"{spec.exponents[1]:+.3g} 1/s negative",
            periods=1,
        )
    return _attractor(
        "unclassified",
        spec,
        f"without excitation: largest exponent {lam:+.3g} 1/s, next "
        f"{spec.exponents[1]:+.3g} 1/s, the state {'still' if still else 'moving'}",
    )
