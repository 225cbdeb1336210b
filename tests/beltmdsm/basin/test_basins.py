"""Basins of attraction (beltmdsm/basin/basins.py) where the T-periodic response and the
4T lock coexist (base set, Vb = 3.88, inside [3.8699, 4.0576] of VALIDATION.md): each
label checked by an independent long run from its start; the same map serially, on a
process pool and on a dask cluster; resumed from its cache; the figure by its data; the
command line end to end."""

import concurrent.futures as cf
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from inprocess import cli

from beltmdsm.attractors.recurrence import IDENTIFY_TOL, LARGEST, claim_radii
from beltmdsm.basin import basins as basins_module
from beltmdsm.basin.basins import basins
from beltmdsm.integrate.events import integrate_events
from beltmdsm.model import Model
from beltmdsm.settings import SolverSettings

ROOT = Path(__file__).resolve().parents[3]
MODEL = Model(Vb=3.88)
PLANE = dict(points=4, x_lo=3.0, x_hi=7.0, y_lo=-8.5, y_hi=-4.5, t_end=600.0)


@pytest.fixture(scope="module")
def serial():
    return basins(MODEL, executor="serial", **PLANE)


def _signature(b):
    return (
        b.labels.tolist(),
        [(a.label, a.attractor.kind, a.attractor.periods, a.fraction) for a in b.attractors],
    )


def test_both_coexisting_responses_have_a_basin_and_each_label_is_where_a_long_run_goes(
    serial,
):
    kinds = [(a.attractor.kind, a.attractor.periods) for a in serial.attractors]
    assert kinds == [("periodic", 1), ("periodic", 4)]
    assert np.all(serial.labels >= 0)
    assert sum(a.fraction for a in serial.attractors) == pytest.approx(1.0)
    assert 0 < serial.attractors[0].fraction < 1
    # an independent check: a plain run of 1500 periods from a start of each label (the
    # 1T response contracts at 0.0097 1/s: its distance falls by e^-23) ends, at phase 0,
    # on one of the points of the attractor its label names
    T = np.pi / 2
    settings = SolverSettings(t_end=1500 * T, rtol=1e-10, atol=1e-10, dt=T / 4, t_discard=0.0)
    base = serial.attractors[0].points[0]
    for label in (0, 1):
        i, j = np.argwhere(serial.labels == label)[0]
        start = base.copy()
        start[:2] = serial.xs[j], serial.ys[i]
        end = integrate_events(MODEL, settings, y0=start).trajectory.state(np.array([1500 * T]))
        points = serial.attractors[label].points
        assert np.min(np.max(np.abs(points - end[:, 0]), axis=1)) < 1e-4


def test_every_start_claimed_early_is_where_an_independent_run_ends(serial):
    # the claim radii are measured from the pilot's trajectories (0.2 for the 4T lock
    # here, twenty times the fixed 1e-2): every start, claimed after a few periods, is
    # checked against a plain run of 600 periods (940 s) from it, whose end at phase 0
    # is near its label's attractor and far from the other
    assert np.mean(serial.periods) < 40
    T = np.pi / 2
    settings = SolverSettings(t_end=600 * T, rtol=1e-10, atol=1e-10, dt=T / 4, t_discard=0.0)
    base = serial.attractors[0].points[0]
    for (i, j), label in np.ndenumerate(serial.labels):
        start = base.copy()
        start[:2] = serial.xs[j], serial.ys[i]
        end = integrate_events(MODEL, settings, y0=start).trajectory.state(np.array([600 * T]))
        near = [np.min(np.max(np.abs(a.points - end[:, 0]), axis=1)) for a in serial.attractors]
        assert near[label] < 0.05 < min(d for k, d in enumerate(near) if k != label)


def test_the_pilot_measures_each_periodic_attractors_claim_radius():
    # half the closest approach of a pilot trajectory bound elsewhere (or nowhere) or of
    # another attractor's points, within [IDENTIFY_TOL, LARGEST]; one that is not
    # periodic keeps its own
    far = np.full((1, 2), 1e3)  # relative distances from the others about 1
    known = [(0, np.zeros((1, 2)), 0.01, 4), (1, far, 0.01, 1), (2, -far, 0.07, 0)]
    rows = [
        {"label": 0, "approach": [0.0, 0.13, 0.5]},
        {"label": 1, "approach": [0.6, 0.0, 0.5]},
        {"label": None, "approach": [0.9, 0.004, 0.5]},
    ]
    radii = [r for _, _, r, _ in claim_radii(known, rows)]
    assert radii == [LARGEST, IDENTIFY_TOL, 0.07]
    rows[1]["approach"][0] = 0.3
    assert claim_radii(known, rows[:2])[0][2] == pytest.approx(0.15)
    # no pilot came near: the other attractors' points bound it (0.5 of 0.2 here)
    near = np.array([[0.25, 0.0]])  # 0.2 of 1 + 0.25 from the origin
    known[1] = (1, near, 0.01, 1)
    assert claim_radii(known, rows[:1])[0][2] == pytest.approx(0.1)


def test_the_map_is_the_same_on_a_process_pool_and_on_a_dask_cluster(serial):
    with cf.ProcessPoolExecutor(max_workers=2) as pool:
        pooled = basins(MODEL, executor=pool, **PLANE)
    assert _signature(pooled) == _signature(serial)
    distributed = pytest.importorskip("distributed")
    with distributed.Client(
        processes=False, n_workers=1, threads_per_worker=2, dashboard_address=None
    ) as client:
        clustered = basins(MODEL, executor=client.get_executor(), **PLANE)
    assert _signature(clustered) == _signature(serial)


def test_an_interrupted_map_resumes_from_its_cache(tmp_path, monkeypatch):
    small = dict(PLANE, points=2)
    first = basins(MODEL, cache_dir=tmp_path, **small)
    assert len(list(tmp_path.glob("*.json"))) == 4

    def boom(*args):
        raise AssertionError("a cached start was computed again")

    monkeypatch.setattr(basins_module, "land", boom)
    again = basins(MODEL, cache_dir=tmp_path, **small)
    assert _signature(again) == _signature(first)


def test_the_figure_draws_the_labels_and_the_attractors_points(serial):
    import matplotlib

    matplotlib.use("Agg")
    ax = serial.plot()
    (mesh,) = ax.collections
    np.testing.assert_array_equal(np.asarray(mesh.get_array()).reshape(4, 4), serial.labels + 1)
    for line, a in zip(ax.lines, serial.attractors):
        np.testing.assert_array_equal(line.get_xdata(), a.points[:, 0])
        np.testing.assert_array_equal(line.get_ydata(), a.points[:, 1])
    assert ax.get_xlabel() == "X1 [m]" and ax.get_ylabel() == "X1' [m/s]"


def test_bad_requests_are_refused_naming_the_argument():
    with pytest.raises(ValueError, match="points"):
        basins(MODEL, points=1)
    with pytest.raises(ValueError, match="x must be one of"):
        basins(MODEL, x="Z")
    with pytest.raises(ValueError, match="x_hi must be a finite number > 2"):
        basins(MODEL, x_lo=2.0, x_hi=1.0)
    # without excitation the map is made (issue 40): tests/beltmdsm/basin/test_basin_stability.py


def test_the_command_prints_attractors_and_grid_as_json(tmp_path):
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    png = tmp_path / "basins.png"
    # the map in the test's process (tests/inprocess.py), the refusal in a real one
    r = cli(
        *["basins", "--Vb", "3.88", "--points", "2"],
        *["--x-from", "3", "--x-to", "7", "--y-from", "-8.5", "--y-to", "-4.5"],
        *["--t-end", "600", "--jobs", "1", "--no-cache", "--json", "--png", str(png)],
    )
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert {"attractors", "grid"} <= set(out) and png.stat().st_size > 0
    for a in out["attractors"]:
        assert {"kind", "periods", "rotation_number", "lyapunov", "fraction"} <= set(a)
    assert len(out["grid"]["labels"]) == 2 and out["grid"]["x"] == "X1"
    r = subprocess.run(
        [sys.executable, "-m", "beltmdsm", "basins", "--x", "Y1", "--y", "Y1"],
        capture_output=True,
        text=True,
        cwd=ROOT,
        env=env,
        timeout=120,
    )
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1 and "--y" in r.stderr
