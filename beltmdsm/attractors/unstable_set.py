"""The unstable set a run from a start on it begins on: a positive Lyapunov exponent there is
that set's instability, not chaos (`unstable_set`; ``beltmdsm lyapunov`` reports it).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from beltmdsm.generated import unforced

from ..errors import NoPeriodicResponse
from ..excitation import excitation_period, initial_state
from ..model import Backend, Model
from ..periodic.floquet import Floquet
from ..periodic.shooting import periodic_response
from .lyapunov import Lyapunov
from .rotation import _CANDIDATES, _HEAD, NEAR, RETURN_TOL, _returns

__all__ = ["unstable_set"]


def unstable_set(
    model: Model, spec: Lyapunov, backend: Backend | None = None
) -> tuple[str, int | None, NDArray[np.float64]] | None:
    """The unstable invariant set a run's averaging window begins on, if any.

    Without excitation: steady sliding (`beltmdsm.excitation.initial_state`) where its
    eigenvalues (`beltmdsm.generated.unforced.eigenvalues`) have a positive real part
    ``sigma``, the window's first sample lies within `NEAR` of it and the run stands
    on it or leaves it (its distance at least doubles over the window: a small cycle
    about it keeps its distance). With excitation:
    a ``k``-periodic response onto which the window's first samples return (to
    `RETURN_TOL`, ``k`` up to four) and Newton's method converges, its Floquet
    multipliers outside the unit circle. A positive exponent of such a run is the
    set's instability (``sigma``, ``ln |mu| / (k T)``), not chaos.

    Parameters
    ----------
    model : Model
        The model that was run.
    spec : Lyapunov
        The run's spectrum and samples (`beltmdsm.attractors.lyapunov.lyapunov`).
    backend : {"python", "numba", None}

    Returns
    -------
    tuple or None
        ``(evidence, periods, state)``: a sentence naming the set, its growth rate
        against the run's exponent and how long the run would take to leave it;
        ``k`` (None for steady sliding); a state on the set. None where the window
        does not begin on an unstable invariant set.

    See Also
    --------
    beltmdsm.attractors.classification.classify : Calls such a run ``unstable``.
    beltmdsm.excitation.equilibrium_start : The default start, off unstable sliding.

    Examples
    --------
    Stribeck's law at ``Vb = 1.9`` without excitation, started exactly on steady
    sliding: the run stays there, and its exponent is the equilibrium's ``sigma``:

    >>> from beltmdsm import Model
    >>> from beltmdsm.attractors.lyapunov import lyapunov
    >>> from beltmdsm.excitation import initial_state
    >>> m = Model(alpha=0.0, friction="stribeck", Vb=1.9)
    >>> spec = lyapunov(m, y0=initial_state(m), t_end=200.0)
    >>> evidence, periods, _ = unstable_set(m, spec)
    >>> periods, "off steady sliding, which is unstable" in evidence
    (None, True)
    """
    y = spec.samples
    scale = 1.0 + float(np.max(np.abs(y)))
    try:
        excitation_period(model)
    except ValueError:
        lam = np.asarray(unforced.eigenvalues(**model.arguments(unforced.eigenvalues)))
        sigma = float(np.max(lam.real))
        eq = initial_state(model)
        d = np.max(np.abs(y - eq), axis=1)
        d0, floor = float(d[0]), np.finfo(float).eps * scale
        # near it and leaving it (or standing on it): a small cycle about it is neither
        leaving = d[-1] >= 2 * max(d0, floor) or float(np.max(d)) <= 16 * floor
        if not (sigma > 0 and d0 <= NEAR * scale and leaving):
            return None
        leave = math.log(scale / max(d0, np.finfo(float).eps * scale)) / sigma
        return (
            f"the run begins its averaging window {d0:.1e} off steady sliding, which is "
            f"unstable (the largest real part of its eigenvalues sigma = {sigma:.4g} 1/s; "
            f"the run's largest exponent {spec.largest:+.4g} 1/s): the exponent is that "
            f"instability, not chaos; the run needs about {leave:.3g} s more to leave it "
            "(raise t_end; a start exactly on it never leaves it, and the default start, "
            "as simulate's, is moved off it along its unstable direction)",
            None,
            eq,
        )
    head = y[: min(len(y), _HEAD)]
    for k in _returns(head, RETURN_TOL)[:_CANDIDATES]:
        try:
            resp = periodic_response(model, periods=k, guess=head[-1], forward=0, backend=backend)
        except NoPeriodicResponse:
            continue
        return _unstable_response(resp, spec, "begins its averaging window on")
    return None


def _unstable_response(resp, spec, where):
    """``unstable_set``'s answer for a converged response, or None where it is stable
    (or grazing: its stability is not known)."""
    f = Floquet.of(resp)
    if f.stable is not False:
        return None
    k = resp.periods
    mu = float(np.max(np.abs(f.multipliers)))
    rate = math.log(mu) / f.period
    return (
        f"the run {where} the {k}T-periodic response (its samples return after {k} "
        f"excitation periods to {RETURN_TOL:g}, Newton's method converges from them, "
        f"residual {resp.residual:.1e}), which is unstable: its largest Floquet "
        f"multiplier |mu| = {mu:.6g}, ln|mu| / ({k} T) = {rate:+.4g} 1/s against the run's "
        f"largest exponent {spec.largest:+.4g} 1/s: the exponent is that response's "
        "instability, not chaos (start off it: beltmdsm.starts.forced.periodic_start "
        "with a perturbation, and run until it has left)",
        k,
        resp.state0,
    )
