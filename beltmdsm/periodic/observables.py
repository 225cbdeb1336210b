"""What a periodic orbit on a branch measures: ranges of X1 and X1', the largest |Vr|,
the mean friction force and the effective friction coefficient.

A branch point keeps the runs of its orbit (`beltmdsm.periodic.base.MapImage`),
so its observables are read from them without solving anything again: each segment of
each of the ``k`` periods is sampled at `SAMPLES_PER_PERIOD` points per excitation
period (at least 8 per segment, both ends included: the extremes at a switch are
exact). An extreme inside a segment is then low by at most ``(h w)^2 / 8`` of the
amplitude (``h`` the sampling step, ``w`` the fastest frequency of the motion):
about 2e-5 relative at the base set's frequencies. The means are time averages over
the ``k`` periods, by the trapezoidal rule on each segment (the friction jumps only at
the switches, which end segments); the forces are those of a run
(`beltmdsm.integrate.trajectory.Trajectory.forces`), per unit mass. This is what
`beltmdsm.continuation.branch.Branch.observables` tabulates and its ``plot`` draws.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from beltmdsm.generated import dynamics

from ..integrate.switching import Mode

if TYPE_CHECKING:
    from .base import MapImage

__all__ = ["OBSERVABLES", "UNITS", "SAMPLES_PER_PERIOD", "orbit_samples", "observables"]

#: The observables of an orbit, by name.
OBSERVABLES = (
    "X1'_amplitude",
    "X1'_min",
    "X1'_max",
    "X1_amplitude",
    "X1_min",
    "X1_max",
    "max_abs_Vr",
    "mean_friction",
    "mu_eff",
)
#: The unit of each observable (the forces per unit mass).
UNITS = {
    **{name: ("m" if name.startswith("X1_") else "m/s") for name in OBSERVABLES[:7]},
    "mean_friction": "m/s^2",
    "mu_eff": "1",
}
#: Samples per excitation period of an orbit.
SAMPLES_PER_PERIOD = 1000


def orbit_samples(
    image: MapImage,
) -> list[tuple[NDArray[np.float64], NDArray[np.float64], Mode]]:
    """The orbit of ``image`` over its ``k`` periods, segment by segment.

    Parameters
    ----------
    image : beltmdsm.periodic.base.MapImage
        The period map at a point of the orbit (it keeps the runs).

    Returns
    -------
    list of (t, states, mode)
        One per segment: ``t`` from the orbit's phase 0 [s], ``states`` ``(4, n)``
        (``X1, X1', X2, X2'``) sampled at `SAMPLES_PER_PERIOD` per excitation period
        (at least 8), both ends of each segment included, and its
        `beltmdsm.integrate.switching.Mode`.

    Raises
    ------
    AttributeError
        Where ``image`` is not a `beltmdsm.periodic.base.MapImage`.

    See Also
    --------
    observables : what is read from them.

    Examples
    --------
    >>> from beltmdsm import Model, periodic_response
    >>> from beltmdsm.periodic.engines import period_map
    >>> r = periodic_response(Model(Vb=5.0))
    >>> pieces = orbit_samples(period_map(r.model)(r.shooting_state))
    >>> [mode.name for _, _, mode in pieces], pieces[0][1].shape[0]
    (['SLIP_BACK', 'SLIP_FORWARD', 'SLIP_BACK'], 4)
    >>> round(float(pieces[-1][0][-1]), 4)  # the period, T = 2 pi / 4
    1.5708
    """
    period = image._map.period
    out = []
    for j, run in enumerate(image._runs):
        for index, (t0, t1, mode) in enumerate(zip(run.starts, run.ends, run.modes)):
            n = max(8, int(np.ceil((t1 - t0) / period * SAMPLES_PER_PERIOD)))
            t = np.linspace(t0, t1, n + 1)
            states = np.asarray(run.segments(t, np.full(t.size, index)), dtype=float)
            out.append((t + j * period, states, Mode(mode)))
    return out


def _forces(model, t, y, mode):
    """Normal and friction force per unit mass along one segment of mode ``mode``, as
    `beltmdsm.integrate.trajectory.Trajectory.forces` gives them for a run."""
    kw = model.arguments
    Fn = dynamics.normal_force(y[2], y[3], **kw(dynamics.normal_force))
    if mode in (Mode.SLIP_BACK, Mode.SLIP_FORWARD):
        sgn = np.full(t.size, int(mode))
        return Fn, dynamics.friction_force(y[1], y[2], y[3], sgn, **kw(dynamics.friction_force))
    if mode == Mode.STICK:  # the force that holds the mass on the belt
        return Fn, -dynamics.free_acceleration(t, y[0], y[1], **kw(dynamics.free_acceleration))
    return Fn, np.zeros(t.size)


def _trapezoid(f, t):
    # written out: numpy 1.x has no np.trapezoid, numpy 2.x deprecates np.trapz
    return 0.5 * float(np.sum((f[1:] + f[:-1]) * np.diff(t)))


def observables(image: MapImage, vb: float) -> dict[str, float]:
    """The `OBSERVABLES` of the orbit of ``image`` at belt speed ``vb`` [m/s].

    Parameters
    ----------
    image : beltmdsm.periodic.base.MapImage
        The period map at a point of the orbit (a branch point keeps one).
    vb : float
        The belt speed [m/s], for ``max_abs_Vr``.

    Returns
    -------
    dict of str to float
        By the names of `OBSERVABLES`, in the units of `UNITS` (the forces per unit
        mass): the extremes from the samples of `orbit_samples` (low by at most about
        2e-5 relative at the base set), the means over the ``k`` periods.

    Raises
    ------
    AttributeError
        Where ``image`` is not a `beltmdsm.periodic.base.MapImage`.

    See Also
    --------
    beltmdsm.continuation.branch.Branch.observables : the table along a branch.
    beltmdsm.periodic.response.PeriodicResponse.ranges : the extremes refined to 1e-12 s.

    Examples
    --------
    >>> from beltmdsm import Model, periodic_response
    >>> from beltmdsm.periodic.engines import period_map
    >>> r = periodic_response(Model(Vb=5.0))
    >>> o = observables(period_map(r.model)(r.shooting_state), vb=5.0)
    >>> {name: round(o[name], 3) for name in ("X1'_min", "X1'_max", "max_abs_Vr", "mu_eff")}
    {"X1'_min": -6.412, "X1'_max": 6.985, 'max_abs_Vr': 11.412, 'mu_eff': 0.506}
    >>> x1_range, velocity_range = r.ranges()  # refined: the samples agree to 1e-4
    >>> abs(o["X1'_max"] - velocity_range[1]) < 1e-4 * velocity_range[1]
    True
    """
    pieces = orbit_samples(image)
    x1 = np.concatenate([y[0] for _, y, _ in pieces])
    v1 = np.concatenate([y[1] for _, y, _ in pieces])
    model = image._map.model
    friction = normal = 0.0
    for t, y, mode in pieces:
        Fn, Ff = _forces(model, t, y, mode)
        friction += _trapezoid(np.broadcast_to(Ff, t.shape), t)
        normal += _trapezoid(np.broadcast_to(Fn, t.shape), t)
    span = pieces[-1][0][-1] - pieces[0][0][0]
    return {
        "X1'_amplitude": 0.5 * float(v1.max() - v1.min()),
        "X1'_min": float(v1.min()),
        "X1'_max": float(v1.max()),
        "X1_amplitude": 0.5 * float(x1.max() - x1.min()),
        "X1_min": float(x1.min()),
        "X1_max": float(x1.max()),
        "max_abs_Vr": float(np.abs(v1 - vb).max()),
        "mean_friction": float(friction / span),
        "mu_eff": friction / normal,
    }
