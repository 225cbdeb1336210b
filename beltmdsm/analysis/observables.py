"""What a periodic orbit on a branch measures: ranges of X1 and X1', the largest |Vr|.

A branch point keeps the runs of its orbit (`beltmdsm.analysis.periodmap.MapImage`),
so its observables are read from them without solving anything again: each segment of
each of the ``k`` periods is sampled at `SAMPLES_PER_PERIOD` points per excitation
period (at least 8 per segment, both ends included: the extremes at a switch are
exact). An extreme inside a segment is then low by at most ``(h w)^2 / 8`` of the
amplitude (``h`` the sampling step, ``w`` the fastest frequency of the motion):
about 2e-5 relative at the base set's frequencies. This is what
`beltmdsm.analysis.branch.Branch.observables` tabulates and its ``plot`` draws.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:
    from .periodmap import MapImage

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
)
#: The unit of each observable.
UNITS = {name: ("m" if name.startswith("X1_") else "m/s") for name in OBSERVABLES}
#: Samples per excitation period of an orbit.
SAMPLES_PER_PERIOD = 1000


def orbit_samples(image: MapImage) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """``(t, states)``: the orbit of ``image`` sampled over its ``k`` periods, ``t``
    from its phase 0 and ``states`` ``(4, n)`` (``X1, X1', X2, X2'``)."""
    period = image._map.period
    times, states = [], []
    for j, run in enumerate(image._runs):
        for index, (t0, t1) in enumerate(zip(run.starts, run.ends)):
            n = max(8, int(np.ceil((t1 - t0) / period * SAMPLES_PER_PERIOD)))
            t = np.linspace(t0, t1, n + 1)
            times.append(t + j * period)
            states.append(np.asarray(run.segments(t, np.full(t.size, index)), dtype=float))
    return np.concatenate(times), np.concatenate(states, axis=1)


def observables(image: MapImage, vb: float) -> dict[str, float]:
    """The `OBSERVABLES` of the orbit of ``image`` at belt speed ``vb`` [m/s]."""
    _, (x1, v1, _, _) = orbit_samples(image)
    return {
        "X1'_amplitude": 0.5 * float(v1.max() - v1.min()),
        "X1'_min": float(v1.min()),
        "X1'_max": float(v1.max()),
        "X1_amplitude": 0.5 * float(x1.max() - x1.min()),
        "X1_min": float(x1.min()),
        "X1_max": float(x1.max()),
        "max_abs_Vr": float(np.abs(v1 - vb).max()),
    }
