"""Basins and basin stability without excitation (issue 40), against references computed
here: an event-driven solve_ivp run with exact Filippov stick, the Hopf point in closed
form, the standard error's formula."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from inprocess import cli
from scipy.integrate import solve_ivp

from beltmdsm.basin import basin_stability as bs_module
from beltmdsm.basin.basin_stability import CHUNK, basin_stability, landscape_of
from beltmdsm.basin.basins import basins
from beltmdsm.model import Model

ROOT = Path(__file__).resolve().parents[3]
#: bSTAB's and pyBasin's friction oscillator (issue 40).
CASE = dict(alpha=0.0, omega1=1.0, beta1=0.05, g=1.0, friction="stribeck", mu_s=1.0, mu_k=0.5,
            v_s=0.5)  # fmt: skip
FLAGS = ["--alpha", "0", "--omega1", "1", "--beta1", "0.05", "--g", "1", "--friction",
         "stribeck", "--mu_s", "1.0", "--mu_k", "0.5", "--v_s", "0.5"]  # fmt: skip
BOX = {"X1": (-2.0, 2.0), "Y1": (0.0, 2.0)}


@pytest.fixture(scope="module")
def ls15():
    return landscape_of(Model(**CASE, Vb=1.5))


# --- the reference: the 1-DOF friction oscillator, typed by hand, exact Filippov stick ---


def _mu(vr):
    return 0.5 + 0.5 * math.exp(-abs(vr) / 0.5)


def _reference(x, v, vb, t_end=500.0, shortcut=True):
    """``"sliding"`` or ``"cycle"``: where a run switching exactly between slip back, slip
    forward and stick (x'' = -0.1 v - x - mu(|v_r|) sgn v_r) is at ``t_end``.

    Two stops, both exact for this system: a run that sticks goes on from the one state
    where every stick ends, whose own run is made once (``shortcut``); a run that comes
    within 1e-3 of steady sliding (700 times closer than the cycle that bounds its
    basin, in the linear range of the focus) stays there.
    """
    eq = 0.5 + 0.5 * math.exp(-vb / 0.5)
    t, y, mode = 0.0, np.array([x, v]), None
    while t < t_end:
        vr = y[1] - vb
        if mode is None:
            mode = 0 if vr == 0 and abs(-0.1 * vb - y[0]) <= 1.0 else (1 if vr > 0 else -1)
        if mode == 0:
            if shortcut:
                return _stick_end_fate(vb, t_end)
            # stick: x' = vb until the spring and damper exceed mu_s g = 1
            x_out = 1.0 - 0.1 * vb  # the edge on the belt's side (x grows)
            t_out = t + (x_out - y[0]) / vb
            if t_out >= t_end:
                y, t = np.array([y[0] + vb * (t_end - t), vb]), t_end
                break
            y, t, mode = np.array([x_out, vb]), t_out, -1
            continue
        s = mode

        def f(_, z, s=s):
            return [z[1], -0.1 * z[1] - z[0] - _mu(z[1] - vb) * s]

        def hit(_, z):
            return z[1] - vb

        def rest(_, z):
            return (z[0] - eq) ** 2 + z[1] ** 2 - 1e-6

        hit.terminal = rest.terminal = True
        hit.direction, rest.direction = -s, -1  # v_r leaves its sign; the run comes in
        sol = solve_ivp(f, (t, t_end), y, events=[hit, rest], rtol=1e-10, atol=1e-12,
                        method="DOP853")  # fmt: skip
        y, t = sol.y[:, -1], sol.t[-1]
        if sol.status == 1 and len(sol.t_events[1]):
            return "sliding"
        if sol.status == 1:
            y = np.array([y[0], vb])
            held = abs(-0.1 * vb - y[0]) <= 1.0  # friction can hold the stick
            mode = 0 if held else -s
    return "sliding" if abs(y[0] - eq) + abs(y[1]) < 1e-3 else "cycle"


_FATES = {}


def _stick_end_fate(vb, t_end):
    if vb not in _FATES:
        _FATES[vb] = _reference(1.0 - 0.1 * vb, vb, vb, t_end, shortcut=False)
    return _FATES[vb]


@pytest.mark.parametrize("samples", [40, pytest.param(200, marks=pytest.mark.slow)])
def test_every_sampled_start_is_classified_like_the_filippov_reference(ls15, samples):
    b = basin_stability(Model(**CASE, Vb=1.5), BOX, samples=samples, seed=3, landscape=ls15)
    names = [a.name for a in b.attractors]
    assert names == ["steady sliding", "stick-slip cycle"]
    mine = ["sliding" if label == 0 else "cycle" for label in b.labels]
    ref = [_reference(x, v, 1.5) for x, v in b.starts[:, :2]]
    assert mine == ref
    assert 0.15 < ref.count("sliding") / samples < 0.5  # both basins are sampled


def test_the_estimate_has_its_standard_error_and_is_reproducible_by_seed(ls15):
    m = Model(**CASE, Vb=1.5)
    a = basin_stability(m, BOX, samples=1200, seed=7, landscape=ls15)
    b = basin_stability(m, BOX, samples=1200, seed=7, landscape=ls15)
    c = basin_stability(m, BOX, samples=1200, seed=8, landscape=ls15)
    np.testing.assert_array_equal(a.starts, b.starts)
    np.testing.assert_array_equal(a.labels, b.labels)
    assert not np.array_equal(a.starts, c.starts)
    p, err = a.fraction(0)
    assert p == np.mean(a.labels == 0)
    assert err == pytest.approx(math.sqrt(p * (1 - p) / 1200), rel=1e-12)
    assert np.all(a.starts[:, 0] >= -2) and np.all(a.starts[:, 1] <= 2)
    # the peer's figure, 0.3100 +- 0.0073 on 4000 starts: within three errors
    assert abs(p - 0.31) < 3 * math.hypot(err, 0.0073)
    assert a.decided["region"] + a.decided["stick"] == 1200


def test_an_interrupted_estimate_keeps_the_chunks_finished(ls15, monkeypatch):
    real, calls = bs_module._cached_chunk, []

    def flaky(*args):
        calls.append(1)
        if len(calls) == 3:
            raise KeyboardInterrupt
        return real(*args)

    monkeypatch.setattr(bs_module, "_cached_chunk", flaky)
    b = basin_stability(Model(**CASE, Vb=1.5), BOX, samples=4 * CHUNK, seed=0, landscape=ls15)
    assert b.interrupted and b.samples == 2 * CHUNK and len(b.labels) == 2 * CHUNK
    assert "interrupted" in repr(b)


def test_a_cached_estimate_is_not_computed_again_and_a_pool_agrees(ls15, tmp_path, monkeypatch):
    import concurrent.futures as cf

    m = Model(**CASE, Vb=1.5)
    first = basin_stability(m, BOX, samples=2 * CHUNK, seed=1, landscape=ls15, cache_dir=tmp_path)
    assert len(list(tmp_path.glob("*.json"))) == 2
    with cf.ProcessPoolExecutor(max_workers=2) as pool:
        pooled = basin_stability(m, BOX, samples=2 * CHUNK, seed=1, landscape=ls15, executor=pool)
    np.testing.assert_array_equal(pooled.labels, first.labels)

    def boom(*args):
        raise AssertionError("a cached chunk was computed again")

    monkeypatch.setattr(bs_module, "_land_chunk", boom)
    again = basin_stability(m, BOX, samples=2 * CHUNK, seed=1, landscape=ls15, cache_dir=tmp_path)
    np.testing.assert_array_equal(again.labels, first.labels)


class _Counting:
    """An executor of 2 workers that runs each task here, at once, and counts them."""

    _max_workers = 2

    def __init__(self):
        self.tasks = []

    def submit(self, fn, *args):
        import concurrent.futures as cf

        self.tasks.append(len(args[2]))
        f = cf.Future()
        f.set_result(fn(*args))
        return f


def test_an_executor_gets_only_chunks_with_starts_to_run_sized_to_its_workers(ls15):
    # issue 40 item 4: at Vb = 1.5 the region rule decides the starts at once (0.01 ms
    # each), less than sending them: nothing goes out; past the stick onset most starts
    # are run, in tasks sized to the workers (8 each), the sets unpickled once per process
    m = Model(**CASE, Vb=1.5)
    ex = _Counting()
    b = basin_stability(m, BOX, samples=400, seed=1, landscape=ls15, executor=ex, cache_dir=None)
    serial = basin_stability(m, BOX, samples=400, seed=1, landscape=ls15, cache_dir=None)
    assert b.decided["region"] == 400 and ex.tasks == []
    np.testing.assert_array_equal(b.labels, serial.labels)

    at = Model(**CASE, Vb=2.0)
    ls = landscape_of(at)
    ex = _Counting()
    bs_module._LANDSCAPES.clear()
    b = basin_stability(at, BOX, samples=160, seed=1, landscape=ls, executor=ex, cache_dir=None)
    assert ex.tasks == [bs_module.MIN_CHUNK] * 6 + [10]  # 160 starts, at least 25 per task
    assert len(bs_module._LANDSCAPES) == 1  # unpickled once for the 7 tasks
    (copy,) = bs_module._LANDSCAPES.values()
    assert copy is not ls and copy.model == ls.model
    serial = basin_stability(at, BOX, samples=160, seed=1, landscape=ls, cache_dir=None)
    np.testing.assert_array_equal(b.labels, serial.labels)
    assert bs_module.chunk_size(4000, ex) == 250 and bs_module.chunk_size(10**6, ex) == CHUNK


def test_bad_requests_are_refused_naming_the_argument():
    m = Model(**CASE, Vb=1.5)
    with pytest.raises(ValueError, match="region"):
        basin_stability(m, {"Z": (0, 1)})
    with pytest.raises(ValueError, match="samples"):
        basin_stability(m, BOX, samples=0)
    with pytest.raises(ValueError, match="without excitation|excitation"):
        basin_stability(Model(Vb=4.0), BOX)


def test_the_map_without_excitation_has_both_basins_split_by_the_unstable_cycle(ls15):
    """Issue 40's refused request: a grid of the plane, the unstable cycle drawn."""
    import matplotlib

    matplotlib.use("Agg")
    b = basins(Model(**CASE, Vb=1.5), points=9, x_lo=-2.0, x_hi=2.0, y_lo=0.0, y_hi=2.0)
    kinds = [(a.attractor.kind, a.period is None) for a in b.attractors]
    assert kinds == [("equilibrium", True), ("periodic", False)]
    assert b.attractors[1].period == pytest.approx(ls15.cycles[1].period)
    assert len(b.boundaries) == 1
    # each label is where the reference run ends
    for i in (0, 4, 8):
        for j in (0, 4, 8):
            want = _reference(b.xs[j], b.ys[i], 1.5)
            assert ("sliding" if b.labels[i, j] == 0 else "cycle") == want
    ax = b.plot()
    assert any(line.get_linestyle() == "--" for line in ax.lines)


def test_the_command_maps_and_samples_without_excitation(tmp_path):
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    argv = ["basins", *FLAGS, "--Vb", "1.5"]
    base = [sys.executable, "-m", "beltmdsm", *argv]
    box = ["--x-from", "-2", "--x-to", "2", "--y-from", "0", "--y-to", "2"]
    png = tmp_path / "map.png"
    # the two runs in the test's process (tests/inprocess.py), the refusal in a real one
    r = cli(*argv, *box, "--points", "4", "--jobs", "1", "--no-cache", "--json", "--png",
            str(png))  # fmt: skip
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert [a["kind"] for a in out["attractors"]] == ["equilibrium", "periodic"]
    assert {"kind", "period", "fraction"} <= set(out["attractors"][1])
    assert len(out["grid"]["labels"]) == 4 and png.stat().st_size > 0
    r = cli(*argv, *box, "--samples", "300", "--seed", "2", "--jobs", "1", "--no-cache",
            "--json")  # fmt: skip
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    fr = [a["fraction"] for a in out["attractors"]]
    assert sum(fr) == pytest.approx(1.0) and out["samples"] == 300 and out["seed"] == 2
    p = fr[0]
    assert out["attractors"][0]["standard_error"] == pytest.approx(math.sqrt(p * (1 - p) / 300))
    r = subprocess.run(
        base + ["--samples", "10"], capture_output=True, text=True, cwd=ROOT, env=env, timeout=120
    )
    assert r.returncode == 2 and "--x-from" in r.stderr


def test_along_the_belt_speed_the_edges_are_the_hopf_point_and_the_stick_onset():
    from beltmdsm.basin.basin_stability_along import basin_stability_along

    r = basin_stability_along(Model(**CASE), BOX, lo=1.0, hi=2.0, points=3, samples=150, seed=0)
    kinds = {(e.kind, e.event): e for e in r.edges}
    hopf = kinds[("hopf", "born")]
    assert hopf.attractor == "steady sliding"
    assert hopf.value == pytest.approx(0.5 * math.log(10.0), abs=1e-9)  # closed form
    onset = kinds[("stick_onset", "dies")]
    assert onset.attractor.startswith("stick-slip cycle")
    assert onset.value == pytest.approx(1.836601, abs=2e-6)
    j_slide, j_cycle = r.names.index("steady sliding"), r.names.index(onset.attractor)
    assert r.fractions[0, j_cycle] == 1.0 and r.fractions[-1, j_slide] == 1.0
    assert 0 < r.fractions[1, j_slide] < 1  # both coexist at 1.5
    table = r.to_pandas()
    assert list(table.columns) == ["Vb", "attractor", "fraction", "standard_error", "samples"]
    assert len(table) == 3 * len(r.names)


def test_the_along_command_prints_the_edges(tmp_path):
    png = tmp_path / "along.png"
    r = cli("basin-stability", *FLAGS, "--param", "Vb",
            "--from", "1.4", "--to", "1.6", "--points", "2", "--samples", "100",
            "--x-from", "-2", "--x-to", "2", "--y-from", "0", "--y-to", "2", "--jobs", "1",
            "--no-cache", "--no-progress", "--json", "--png", str(png))  # fmt: skip
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert out["values"] == [1.4, 1.6] and out["samples"] == 100
    names = [a["name"] for a in out["attractors"]]
    assert "steady sliding" in names and png.stat().st_size > 0


def test_a_forced_models_basins_at_vb_4_are_unchanged():
    """The forced path is today's: the 3 x 3 map at Vb = 4 that main computed before
    issue 40 (commit d1c63ab, the same call), label for label, and its attractors."""
    b = basins(Model(Vb=4.0), points=3, executor="serial", t_end=600.0)
    assert b.labels.tolist() == [[1, 1, 1], [1, 0, 1], [1, 1, 1]]
    assert [(a.attractor.kind, a.attractor.periods, a.period) for a in b.attractors] == [
        ("periodic", 1, None),
        ("periodic", 4, None),
    ]
    np.testing.assert_allclose(b.xs, [-10.41013643060684, 4.174740165364508, 18.759616761335856])
    assert not b.boundaries


def test_a_box_in_all_four_states_lands_where_a_plain_run_ends(ls15):
    """Starts off the plane (the normal motion disturbed) are run until the normal motion
    has settled; each label is where a plain 500 s run of the full model ends."""
    from beltmdsm.integrate.events import integrate_events
    from beltmdsm.settings import SolverSettings

    m = Model(**CASE, Vb=1.5)
    x2 = ls15.equilibrium.state[2]
    box = {**BOX, "X2": (0.9 * x2, 1.1 * x2), "Y2": (-0.1, 0.1)}
    b = basin_stability(m, box, samples=12, seed=0, landscape=ls15)
    assert b.decided["stick"] > 0 and np.ptp(b.starts[:, 3]) > 0
    settings = SolverSettings(t_end=500.0, rtol=1e-10, atol=1e-12, dt=1.0, t_discard=0.0)
    eq = ls15.equilibrium.state
    for start, label in zip(b.starts, b.labels):
        tr = integrate_events(m, settings, y0=start).trajectory
        tail = tr.state(np.linspace(490.0, 500.0, 50))
        resting = np.max(np.abs(tail[:2] - eq[:2, None])) < 1e-3
        assert label == (0 if resting else 1)


def test_ctrl_c_on_the_command_prints_the_estimate_of_the_starts_finished():
    import signal
    import time

    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    p = subprocess.Popen(
        [sys.executable, "-m", "beltmdsm", "basins", *FLAGS, "--Vb", "1.5", "--x-from", "-2",
         "--x-to", "2", "--y-from", "0", "--y-to", "2", "--samples", "2000000", "--jobs", "1",
         "--no-cache"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=ROOT, env=env,
    )  # fmt: skip
    clock = time.monotonic()
    seen = ""
    while "basin stability:" not in seen and time.monotonic() - clock < 240:
        seen += p.stderr.read(1)  # the progress bar starts once the sets are computed
    time.sleep(2.0)
    p.send_signal(signal.SIGINT)
    out, _ = p.communicate(timeout=120)
    assert p.returncode == 130, out
    assert "interrupted: the estimate is of the" in out
    n = int(out.split("BasinStability(")[1].split(" starts")[0])
    assert 0 < n < 2_000_000 and n % CHUNK == 0
