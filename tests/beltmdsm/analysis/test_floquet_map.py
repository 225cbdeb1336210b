"""Exact two-parameter maps (beltmdsm.analysis.floquet_map) against bands and pointwise verdicts.

References: `beltmdsm.analysis.band.floquet_band` on the map's rows, `floquet()` from
scratch at points of a coarse grid, and the closed-form interval of the paper's linear
analysis (`generated.stability.unstable_interval`).
"""

import numpy as np
import pytest

from beltmdsm.analysis.band import floquet_band
from beltmdsm.analysis.floquet import NoPeriodicResponse, floquet
from beltmdsm.analysis.floquet_map import LINEAR_POINTS, floquet_map
from beltmdsm.model import Model
from generated import stability


def test_the_map_rows_are_the_bands_and_the_verdicts_of_floquet():
    result = floquet_map("Vb", 0.5, 12.0, "beta1", 0.05, 0.35, rows=4)
    assert {c.kind for c in result.curves} == {"neimark_sacker", "tangency", "grazing"}
    assert all(len(c.y) == 4 for c in result.curves)
    for y, unstable in zip(result.rows, result.unstable):
        band = floquet_band("Vb", 0.5, 12.0, beta1=float(y))
        assert len(unstable) == len(band.unstable) == 1
        edges = {e.kind: e for e in band.edges}
        # the map's edges to its accuracy, the band's to theirs
        assert unstable[0][0] == pytest.approx(
            band.unstable[0][0], abs=edges["neimark_sacker"].accuracy + 1e-4
        )
        assert unstable[0][1] == pytest.approx(band.unstable[0][1], abs=1e-6)
        # off the edges, floquet() from scratch says the same
        for x in np.linspace(0.6, 11.9, 12):
            if min(abs(x - v) for v in unstable[0]) < 0.1:
                continue
            try:
                verdict = floquet(Vb=x, beta1=float(y)).stable is not True
            except NoPeriodicResponse:
                verdict = True
            assert verdict == (unstable[0][0] <= x <= unstable[0][1]), (y, x)
    # the paper's linear analysis on the same rows, against its closed-form interval
    # (generated.stability.unstable_interval), to the map's grid of x
    resolution = (12.0 - 0.5) / (LINEAR_POINTS - 1)
    for y, linear in zip(result.rows, result.linear):
        lower, upper = stability.unstable_interval(**Model(beta1=float(y)).params)
        ((a, b),) = linear
        assert a == pytest.approx(max(float(lower), 0.5), abs=resolution)
        assert b == pytest.approx(float(upper), abs=resolution)
    out = result.as_dict()
    assert set(out["curves"][0]) >= {"kind", "x", "y", "accuracy", "frequency"}
    assert len(out["unstable"]) == len(out["linear"]) == 4


def test_bad_axes_are_refused():
    with pytest.raises(ValueError, match="differ"):
        floquet_map("Vb", 1.0, 2.0, "Vb", 1.0, 2.0)
    with pytest.raises(ValueError, match="model parameters"):
        floquet_map("Vbelt", 1.0, 2.0, "beta1", 0.1, 0.2)
    with pytest.raises(ValueError, match="rows"):
        floquet_map("Vb", 1.0, 2.0, "beta1", 0.1, 0.2, rows=1)
