"""What a periodic orbit of any model measures: the extremes of its states and of the slip
velocity (the observables of a branch point, `beltmdsm.continuation.oscillator_forced`).

The orbit is run once over its period from its state at phase 0, sampled ``samples``
times (`beltmdsm.oscillator.hybrid.flow`); each extreme is the sampled one refined by
the vertex of the parabola through it and its two neighbours. On a smooth stretch of
the orbit the vertex's error is of order ``(omega h)^4`` of the amplitude (``h`` the
sampling step, ``omega`` the orbit's frequency): below 2e-9 of it at 2048 samples a
period. At a kink (a stick's flat top, a reversal) the parabola is not refined past
the samples' bracket (its vertex stays between the neighbours).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .hybrid import flow
from .system import System

__all__ = ["SAMPLES", "orbit_observables", "slip_margin"]

#: Samples of one orbit (its period) for the extremes.
SAMPLES = 2048


def _extreme(values: NDArray[np.float64], sign: float) -> float:
    """The largest of ``sign * values`` (a periodic sampling: the last sample is the
    first's image) refined by the parabola's vertex, times ``sign``."""
    v = sign * values[:-1]
    i = int(np.argmax(v))
    a, b, c = v[i - 1], v[i], v[(i + 1) % v.size]
    curvature = a - 2.0 * b + c
    if curvature >= 0.0 or a == b or c == b:  # flat, a kink, or a stick's plateau edge
        return float(sign * b)
    offset = 0.5 * (a - c) / curvature
    if abs(offset) > 1.0:
        return float(sign * b)
    return float(sign * (b - 0.25 * (a - c) * offset))


def orbit_observables(
    system: System,
    state: NDArray[np.float64],
    period: float,
    *,
    samples: int = SAMPLES,
    rtol: float = 1e-11,
    atol: float = 1e-11,
) -> dict[str, float]:
    """The extremes of an orbit's states and slip velocity (module docstring).

    Parameters
    ----------
    system : System
    state : ndarray (2n,)
        The orbit's state at ``t = 0`` (phase 0 of the excitation).
    period : float
        The orbit's period [s].
    samples : int
    rtol, atol : float

    Returns
    -------
    dict of str to float
        ``<state>_min``, ``<state>_max``, ``<state>_amplitude`` (half the range) for each
        of the model's states, then ``v_r_min``, ``v_r_max`` and ``max_abs_v_r``.

    See Also
    --------
    slip_margin : how far the slip velocity stays from 0.

    Examples
    --------
    >>> import math
    >>> s = System("belt_1dof", Vb=3.0, beta1=0.0, mu_s=0.1, alpha_t=0.5, Omega_t=2.0)
    >>> from beltmdsm.oscillator import forced_response
    >>> r = forced_response(s)
    >>> obs = orbit_observables(s, r.state, r.period)
    >>> # undamped, linear in slip: x = mu g / w^2 + a W^2 / (w^2 - W^2) sin(W t)
    >>> round(obs["x_amplitude"], 8), round(abs(0.5 * 4 / (1 - 4)), 8)
    (0.66666667, 0.66666667)
    """
    found: list = []
    flow(system, 0.0, state, period, dt=period / samples, samples=found, rtol=rtol, atol=atol)
    t = np.concatenate([np.atleast_1d(c[0]) for c in found])
    y = np.concatenate([np.atleast_2d(c[1]) for c in found])
    keep = t <= period * (1.0 + 1e-12)
    t, y = t[keep], y[keep]
    slip = system.kernels.slip_velocity
    vr = np.array([float(slip(ti, yi, system.p)) for ti, yi in zip(t, y)])
    out: dict[str, float] = {}
    for name, column in zip(system.states, y.T):
        lo, hi = _extreme(column, -1.0), _extreme(column, 1.0)
        out.update({f"{name}_min": lo, f"{name}_max": hi, f"{name}_amplitude": 0.5 * (hi - lo)})
    out["v_r_min"], out["v_r_max"] = _extreme(vr, -1.0), _extreme(vr, 1.0)
    out["max_abs_v_r"] = max(-out["v_r_min"], out["v_r_max"])
    return out


def slip_margin(observables: dict[str, float]) -> float:
    """How far a pure-slip orbit's slip velocity stays from 0: ``-v_r_max`` for an orbit
    that slips backwards (``v_r < 0``) throughout, ``v_r_min`` for one that slips
    forwards; it vanishes where the orbit grazes ``v_r = 0`` (the onset of stick or of
    reversal) and is negative on an orbit that reaches it.

    Examples
    --------
    >>> slip_margin({"v_r_min": -3.0, "v_r_max": -1.0}), slip_margin({"v_r_min": 0.5, "v_r_max": 2})
    (1.0, 0.5)
    """
    lo, hi = observables["v_r_min"], observables["v_r_max"]
    return -hi if abs(hi) <= abs(lo) else lo
