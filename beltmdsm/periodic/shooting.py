"""The periodic response of Eq. (4) by shooting: `periodic_response`.

* **Periodic response.** `periodic_response` finds the state at phase 0 that the
  period map returns to (`beltmdsm.periodic.engines.period_map`, the engine the facts
  of the model's laws allow), by Newton's method with the map's Jacobian (damped
  steps, `beltmdsm.periodic.newton.fixed_point`). The first guess is the orbit that
  slides backwards throughout, which is exact where the friction never reverses; a
  continuation passes the previous orbit instead. Where Newton's method fails, the
  period map iterated forward from the sliding orbit (`FORWARD_PERIODS`) finds a
  stable response next to a grazing point.
* **Phase-locked responses** (``periods = k > 1``): the response of ``k T``, a fixed
  point of the ``k``-fold map. Without a guess it is seeded from the attractor of the
  period map iterated from rest (`beltmdsm.periodic.locked.map_stroboscope`,
  `SEED_PERIODS`), where that attractor locks at ``k`` periods
  (docs/modelling.md#bifurcations).
* **Without excitation** (`beltmdsm.excitation.is_autonomous`) there is no period to take
  the phase from: `periodic_response` computes the self-excited cycle instead
  (`beltmdsm.periodic.cycle`: the period found by shooting with a phase condition), with
  ``autonomous`` set (`beltmdsm.periodic.response.response_of_cycle`).

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from .._calling import public
from ..arguments import count, state
from ..errors import NoPeriodicResponse, Refused, ShorterPeriod
from ..excitation import excitation_period, initial_state, is_autonomous
from ..model import Backend, Model, as_model
from .base import Engine
from .engines import period_map
from .locked import LOCK_LIMIT, NotLocked, map_stroboscope, minimal_periods
from .newton import fixed_point
from .response import PeriodicResponse, response_from, response_of_cycle

__all__ = [
    "periodic_response",
    "FORWARD_PERIODS",
    "SEED_PERIODS",
    "MAX_SEED_PERIODS",
]

#: Periods of forward iteration of the tangential period map where Newton's method
#: fails (a stable response next to a grazing point).
FORWARD_PERIODS = 200
#: Forward iteration gives up when its step has not shrunk below this fraction over
#: this many periods: converging to a response with |mu| <= 0.995 it shrinks by 0.88
#: or more, while next to no stable response (another attractor, a drift) it does not.
_FORWARD_WINDOW = 25
_FORWARD_PROGRESS = 0.9
#: The seed of a response of ``k > 1`` periods: the period map iterated from rest for
#: this many periods to settle, then as many again sampled (the last 40% of a run of
#: 1000 s at the base set; the lock is found there at every point of
#: tests/beltmdsm/periodic/test_locked.py, as the run from rest of Eq. (4) finds it).
SEED_PERIODS = (400, 256)
#: The longest response looked for without a guess: a lock at ``k`` periods is seen in
#: more than ``2 k`` samples (`beltmdsm.periodic.locked.stroboscope`), of which the
#: seed has ``SEED_PERIODS[1]``.
MAX_SEED_PERIODS = (SEED_PERIODS[1] - 1) // 2


def _cycle_response(model, guess, max_iter, backend, periods, engine):
    """`periodic_response` without excitation: the self-excited cycle."""
    from .cycle import Cycle, cycle

    if periods != 1:
        raise ValueError(
            f"periods must be 1 without excitation (a self-excited cycle has no "
            f"excitation period to count); got {periods!r}"
        )
    if engine not in (None, "general"):
        raise ValueError(
            f"engine={engine!r}: a self-excited cycle is computed on the general path only"
        )
    if isinstance(guess, PeriodicResponse):
        guess = guess.cycle if guess.autonomous else None
    if isinstance(guess, Cycle):
        return response_of_cycle(
            cycle(model, guess.state, guess.period, max_iter=max_iter, backend=backend)
        )
    if guess is not None:
        raise ValueError(
            "a guess of a self-excited cycle needs its period: pass a PeriodicResponse "
            "or a beltmdsm.periodic.cycle.Cycle, or call beltmdsm.periodic.cycle.cycle"
        )
    return response_of_cycle(cycle(model, max_iter=max(max_iter, 30), backend=backend))


@public(models=True)
def periodic_response(
    model: Model | Mapping[str, Any] | None = None,
    *,
    guess: Sequence[float] | PeriodicResponse | None = None,
    max_iter: int = 20,
    forward: int = FORWARD_PERIODS,
    backend: Backend | None = None,
    periods: int = 1,
    engine: Engine | None = None,
) -> PeriodicResponse:
    """The periodic response of Eq. (4) by shooting (module docstring).

    Newton's method from ``guess`` (or the backward-sliding orbit); where it fails,
    the period map is iterated forward from the sliding orbit for up to ``forward``
    periods (it converges to a stable periodic response, where Newton's method may
    not, next to a grazing point) and Newton's method polishes the result. The period
    map is the closed-form one where the model's laws allow it, else the general one
    (`beltmdsm.periodic.engines.period_map`); the result's ``engine`` says which.

    Parameters
    ----------
    model : Model or dict, optional
        The model (default: the base set); ``**kw``: parameters and options.
    guess : array_like (2,) or (4,), or PeriodicResponse, optional
        The state at phase 0 to start Newton's method from (a continuation's
        predictor, a neighbour on a branch): ``(X1, X1', X2, X2')`` or the tangential
        ``(X1, X1')`` (on the general path completed by the sliding orbit's normal
        state); default the backward-sliding orbit (``periods = 1``) or the attractor
        of the period map iterated from rest (``periods > 1``).
    max_iter : int
    forward : int
        Periods of forward iteration after Newton's method fails (0: none;
        ``periods = 1`` only).
    backend : {"python", "numba", None}
    periods : int
        ``k >= 1``: the response of ``k`` excitation periods (phase-locked for ``k >
        1``), by shooting on the ``k``-fold map.
    engine : {"closed_form", "general", None}
        The period map (`beltmdsm.periodic.engines.period_map`); None: the one the
        model's laws allow.

    Without excitation (`beltmdsm.excitation.is_autonomous`) the response is the self-excited
    cycle (`beltmdsm.periodic.cycle.cycle`, ``autonomous`` set): seeded from a run off
    unstable steady sliding, or from ``guess`` (a `PeriodicResponse` of a cycle or a
    `beltmdsm.periodic.cycle.Cycle`: a neighbour); ``forward`` does not apply.

    Returns
    -------
    PeriodicResponse
        With ``periods = k`` and ``period = k T``.

    Raises
    ------
    ValueError
        Naming the argument: bad parameters, a tension law that does not exist, an
        excitation without a period (zero or incommensurate frequencies), ``periods``
        or ``max_iter`` not an integer >= 1 (a bool is not one), ``forward`` not an
        integer >= 0, a guess that is not 2 or 4 finite real numbers, or an unknown
        engine; `beltmdsm.errors.Refused` for ``periods > MAX_SEED_PERIODS`` without
        a guess (the seed cannot tell such a lock).
    beltmdsm.model.Unsupported
        For ``engine="closed_form"`` where the model's laws lack a fact it needs.
    NoPeriodicResponse
        (a RuntimeError) If no periodic response is found; for ``periods > 1``
        without a guess, where the attractor of the period map does not lock at
        ``k`` periods (the message says what it does instead): `beltmdsm.errors.ShorterPeriod` where
        it locks at a divisor ``d`` of ``k`` (its orbit is ``k T``-periodic too, a
        response of ``d`` periods; ``floquet --periods 8 --Vb 5`` reports the 4T one).

    See Also
    --------
    beltmdsm.periodic.floquet.floquet : the response's multipliers.
    beltmdsm.starts.forced.periodic_start : a run's start on it.
    beltmdsm.continuation.branch.branch : the response continued in a parameter.
    beltmdsm.periodic.cycle.cycle : the self-excited cycle of a model without excitation.

    Examples
    --------
    >>> from beltmdsm import Model, periodic_response
    >>> r = periodic_response(Model(Vb=5.0))
    >>> r.engine, r.periods, round(r.period, 4), r.residual < 1e-10
    ('closed_form', 1, 1.5708, True)

    A neighbour's response as the guess (a continuation's step):

    >>> near = periodic_response(Model(Vb=5.2), guess=r)
    >>> near.residual < 1e-10, round(float(near.state0[0]), 3)  # X1 at phase 0 [m]
    (True, 4.488)

    The response of 4 periods; asked for 8, the attractor that locks at 4 is named:

    >>> periodic_response(Model(Vb=5.0), periods=4).periods
    4
    >>> periodic_response(Model(Vb=5.0), periods=8)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    beltmdsm.errors.ShorterPeriod: no response of minimal period 8 periods found: ... 4 periods, ...
    """
    model = as_model(model)
    periods = count("periods", periods, 1)
    if model.model != "paper":  # another registered model: the generic runtime
        from ..oscillator import api

        return api.periodic_response(model, guess, periods, engine=engine)
    max_iter = count("max_iter", max_iter, 1)
    forward = count("forward", forward, 0)
    if is_autonomous(model):
        return _cycle_response(model, guess, max_iter, backend, periods, engine)
    if isinstance(guess, PeriodicResponse):
        guess = guess.state0
    if guess is not None:
        guess = state("guess", guess, (2, 4), "the state at phase 0")
    elif periods > MAX_SEED_PERIODS:
        raise Refused(
            f"periods must be <= {MAX_SEED_PERIODS} without a guess: the seed samples "
            f"{SEED_PERIODS[1]} periods of the period map, and a lock at k periods needs "
            f"more than 2 k (SEED_PERIODS, beltmdsm/periodic/shooting.py); got {periods}",
            "periods",
        )
    excitation_period(model)
    pmap = period_map(model, periods, backend, engine)
    if guess is not None:
        guess = pmap.guess(guess)
    if pmap.periods > 1 and guess is not None:
        return response_from(pmap, fixed_point(pmap, guess, max_iter))
    if pmap.periods > 1:
        seed, locks = _locked_seed(pmap)
        if locks != pmap.periods:
            raise ShorterPeriod(pmap.periods, locks, "the period map iterated from rest locks at")
        point = fixed_point(pmap, seed, max_iter)
        shortest = minimal_periods(point.image, pmap.periods)
        if shortest != pmap.periods:
            raise ShorterPeriod(
                pmap.periods,
                shortest,
                "from the attractor of the period map iterated from rest, Newton's method "
                "finds a response of",
            )
        return response_from(pmap, point)
    start = pmap.sliding_guess() if guess is None else guess
    try:
        point = fixed_point(pmap, start, max_iter)
    except NoPeriodicResponse as newton_failed:
        if not forward:
            raise
        x, steps = pmap.sliding_guess(), []
        for k in range(int(forward)):
            xT = pmap.step(x)
            steps.append(float(np.max(np.abs(xT - x))))
            if steps[-1] <= 1e-7 * (1 + np.max(np.abs(x))):
                break
            if k >= _FORWARD_WINDOW and steps[-1] > _FORWARD_PROGRESS * steps[-1 - _FORWARD_WINDOW]:
                raise NoPeriodicResponse(
                    f"{newton_failed}; nor does the period map, iterated from the sliding "
                    f"orbit: its step does not shrink over {_FORWARD_WINDOW} periods "
                    f"({steps[-1 - _FORWARD_WINDOW]:.2e} to {steps[-1]:.2e})"
                ) from None
            x = xT
        else:
            raise NoPeriodicResponse(
                f"{newton_failed}; nor does the period map, iterated "
                f"{forward} periods from the sliding orbit, settle"
            ) from None
        point = fixed_point(pmap, x, max_iter)
    return response_from(pmap, point)


def _locked_seed(pmap):
    """The last sample of the attractor of the period map from rest, and the number of
    periods it locks at: ``k`` or a divisor of it (a ``k/d``-periodic orbit is
    ``k``-periodic too)."""
    k = pmap.periods
    strobe = map_stroboscope(
        pmap,
        pmap.shooting(initial_state(pmap.model)),
        *SEED_PERIODS,
        "the period map iterated from rest",
        max(k, LOCK_LIMIT),
    )
    locks = strobe.candidate
    if locks is None or k % locks:
        what = f"locks at {_periods(locks)}" if locks else NotLocked.of(strobe).text()
        raise NoPeriodicResponse(
            f"no response of {_periods(k)} found: the period map iterated from rest {what}"
        )
    return strobe.samples[-1], locks


def _periods(k: int) -> str:
    return "1 period" if k == 1 else f"{k} periods"
