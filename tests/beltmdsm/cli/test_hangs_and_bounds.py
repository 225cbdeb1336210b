"""Issue 28, section 2: hangs, lost work and unbounded resources, end to end.

Each command-line report runs the command that showed it in a real subprocess (its
exit status, its stderr, a signal sent to it), with a time bound where it hung; the
compiled loops are checked where they were unbounded, in plain Python.
"""

import json
import os
import signal
import subprocess
import sys
import time
import types
from pathlib import Path

import numpy as np
import pytest

from beltmdsm.integrate import _compiled, _dop853, _roots, _switch_scan
from beltmdsm.model import Model

ROOT = Path(__file__).resolve().parents[3]
ENV = {**os.environ, "PYTHONPATH": str(ROOT)}
#: Den Hartog's oscillator at the undamped 2:1 resonance (the report's flags).
DEN_HARTOG = [
    "--omega1", "1", "--beta1", "0", "--Vb", "0", "--alpha_n", "0", "--alpha_t", "4",
    "--Omega_t", "0.5", "--Omega_n", "0.5", "--phase_t", "1.5707963267948966",
    "--mu_s", "0.0305810397553517",
]  # fmt: skip


def _cli(*argv, timeout=120):
    """``python -m beltmdsm argv`` in a subprocess: (returncode, stdout, stderr)."""
    out = subprocess.run(
        [sys.executable, "-m", "beltmdsm", *argv],
        capture_output=True,
        text=True,
        timeout=timeout,
        env=ENV,
        cwd=ROOT,
    )
    return out.returncode, out.stdout, out.stderr


def _one_line(stderr):
    lines = [ln for ln in stderr.splitlines() if ln.strip() and "warning:" not in ln]
    assert len(lines) == 1 and "Traceback" not in stderr, stderr
    return lines[0]


# ------------------------------------------------------------ 1. the golden-section dip


def _counted(f, limit=10_000):
    """``f`` that counts its calls and raises past ``limit`` (a hang fails, not hangs)."""
    calls = [0]

    def g(t):
        calls[0] += 1
        if calls[0] > limit:
            raise RuntimeError("the search does not end")
        return f(t)

    return g, calls


@pytest.mark.parametrize("module", ["_dop853", "_switch_scan"])
def test_dip_ends_at_ulp_resolution_late_in_a_long_run(module):
    # the report: at t ~ 1000 s a step of 1e-6 s asks the golden section for a
    # bracket of 1e-8 h = 1e-14 s, below one ulp of t (1.1e-13): it never ended
    tm, lo, hi = 1000.0 + 3e-7, 1000.0, 1000.0 + 1e-6
    f, calls = _counted(lambda t: (t - tm) ** 2 + 1e-30)  # a dip that stays inside
    if module == "_dop853":
        namespace = {**vars(_dop853), "_surface_at": lambda *a: f(a[8])}
        dip = types.FunctionType(_dop853._dip.__code__, namespace)
        t, ft = dip(None, None, None, 0, None, None, lo, hi - lo, lo, hi, None)
    else:
        namespace = {**vars(_switch_scan), "_inside_at": lambda t, j, ctx: f(t)}
        dip = types.FunctionType(_switch_scan._dip.__code__, namespace)
        t, ft = dip(lo, hi, 0, None)
    assert calls[0] <= _roots.GOLDEN_STEPS + 2
    # the minimum located to a few ulps of t (the closed form: t = tm)
    assert abs(t - tm) <= 8 * np.spacing(tm) and 0 < ft <= 1e-30 + (8 * np.spacing(tm)) ** 2


def test_simulate_with_a_stiff_contact_finishes_and_matches_superposition():
    # the report: `simulate --omega2 1000 --t-end 2000` ran for ever (the same search);
    # omega2 = 1e5 hangs on main within 20 s of simulated time
    from beltmdsm import simulate

    start = time.perf_counter()
    rc, out, err = _cli("simulate", "--omega2", "1e5", "--t-end", "20", "--json", timeout=150)
    assert rc == 0, err
    assert time.perf_counter() - start < 150
    events = json.loads(out)
    assert events["status"] == "done" and events["solver"] == "events"
    # an independent integrator: the closed-form superposition of the same case
    ref = simulate(Model(omega2=1e5), t_end=20.0, solver="superposition").summary
    assert ref.solver == "superposition"
    assert events["n_switches"] == ref.n_switches
    for name in ("peak_Omega", "vr_min", "vr_max"):
        assert events[name] == pytest.approx(getattr(ref, name), rel=1e-6, abs=1e-8)


@pytest.mark.slow
def test_simulate_the_reported_stiff_contact_finishes():
    rc, out, err = _cli("simulate", "--omega2", "1000", "--t-end", "2000", "--json", timeout=600)
    assert rc == 0 and json.loads(out)["status"] == "done", err


def _line_kernels(rate, limit=100_000):
    calls = [0]

    def field(t, X1, Y1, X2, Y2, mode):
        calls[0] += 1  # a loop that does not end fails the test, not hangs it
        if calls[0] > limit:
            raise RuntimeError("the integrator does not stop")
        return (rate, rate * X1, 0.0, 0.0)

    def surfaces(t, X1, Y1, X2, Y2):
        return (X1 - 1e300,)

    def rates(t, X1, Y1, X2, Y2, mode):
        return (rate,)

    return field, surfaces, rates


def _advance(kernels, y0, t_end, **kw):
    advance = _compiled._python(_compiled._ADVANCE, kernels)
    args = ((), (), (), 0.0, np.array([0]), np.array([1.0]), 0.0, y0, t_end, 0.0)
    return advance(*args, 1e-10, 1e-10, np.inf, **kw)


def test_dop853_stops_on_a_state_that_is_not_finite():
    # a NaN step size compares false with every bound: the step loop never ended
    out = _advance(_line_kernels(1.0), np.array([np.nan, 0.0, 0.0, 0.0]), 1.0)
    assert out[0] == _dop853.STATUS_NOT_FINITE and out[1] == 0


def test_dop853_stops_after_its_steps_bound():
    out = _advance(_line_kernels(1.0), np.zeros(4), 100.0, max_steps=5)
    status, n, ts, hs = out[:4]
    assert status == _dop853.STATUS_TOO_MANY_STEPS and n == 5 and ts.size == 5
    # the five steps are a plain run's first five (the bound ends it, changes nothing)
    ref = _advance(_line_kernels(1.0), np.zeros(4), 100.0)
    assert ref[0] == _dop853.STATUS_END and ref[1] > 5
    np.testing.assert_array_equal(ts, ref[2][:5])


# ------------------------------------------------------------ 2. Den Hartog, undamped


def test_den_hartog_responses_end_and_floquet_says_not_isolated():
    from beltmdsm import simulate
    from beltmdsm.model import as_model

    rc, out, err = _cli("responses", *DEN_HARTOG, "--json", timeout=150)
    assert rc == 0, err
    found = json.loads(out)["responses"]
    assert found
    # the response exists: a run from its state returns there after one period (the
    # event-driven integrator, not the period map), and a multiplier is 1
    flags = dict(zip(DEN_HARTOG[::2], map(float, DEN_HARTOG[1::2])))
    model = as_model(None, **{k.lstrip("-"): v for k, v in flags.items()})
    slides = [r for r in found if r["n_sticks"] == 0]
    assert slides, found
    r = slides[0]
    assert r["period"] == pytest.approx(4 * np.pi, rel=1e-14)
    assert r["max_abs_multiplier"] == pytest.approx(1.0, abs=1e-9)
    sim = simulate(model, y0=r["state0"], t_end=r["period"], rtol=1e-12, atol=1e-12)
    end = sim.trajectory.state(np.array([r["period"]]))[:, 0]
    np.testing.assert_allclose(end, r["state0"], atol=1e-7)
    # its verdict says so
    from beltmdsm.cli.text.periodic import _isolation

    mus = [complex(re, im) for re, im in r["multipliers"]]
    assert "not isolated" in _isolation(types.SimpleNamespace(multipliers=mus))
    assert _isolation(types.SimpleNamespace(multipliers=[0.9999, 0.5])) == ""
    # floquet: not "no periodic response found" alone, but why
    rc, out, err = _cli("floquet", *DEN_HARTOG, timeout=120)
    line = _one_line(err)
    assert rc == 2 and out == ""
    assert "the response is not isolated: a multiplier is 1 (I - M singular" in line


# ------------------------------------------------------------ 3. Ctrl-C


def test_ctrl_c_stops_a_process_pool_sweep_and_keeps_its_finished_points(tmp_path):
    argv = ["sweep", "--param", "Vb", "--values", *map(str, range(1, 9)), "--t-end", "1500"]
    argv += ["--jobs", "2", "--cache-dir", str(tmp_path), "--no-progress"]
    proc = subprocess.Popen(
        [sys.executable, "-m", "beltmdsm", *argv],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=ENV,
        cwd=ROOT,
        start_new_session=True,  # its own process group, as a terminal's Ctrl-C sees it
    )
    try:
        deadline = time.monotonic() + 180
        while not list(tmp_path.glob("*.json")) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert list(tmp_path.glob("*.json")), "no point finished"
        # Ctrl-C twice to the group (the main process and its workers)
        os.killpg(proc.pid, signal.SIGINT)
        sent = time.monotonic()
        time.sleep(0.05)
        os.killpg(proc.pid, signal.SIGINT)
        out, err = proc.communicate(timeout=30)
        stopped = time.monotonic() - sent
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    assert proc.returncode == 130 and out == ""
    assert stopped < 15  # 8 points of ~2 s each on 2 workers would have taken longer
    line = _one_line(err)
    assert "interrupted" in line and "every point finished is kept in the cache" in line
    received = int(line.split("stopped after ")[1].split(" of 8 points")[0])
    files = list(tmp_path.glob("*.json"))
    # a worker writes its point before this process receives it
    assert 1 <= len(files) < 8 and received <= len(files)
    for f in files:
        assert json.loads(f.read_text())["row"]["status"] == "done"


def test_ctrl_c_in_a_run_prints_one_line():
    proc = subprocess.Popen(
        [sys.executable, "-m", "beltmdsm", "simulate", "--t-end", "60000"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=ENV,
        cwd=ROOT,
    )
    try:
        # the progress bar shows once the run has taken 2 s: it is in the integrator
        seen = ""
        while "simulate:" not in seen:
            chunk = proc.stderr.read(1)
            assert chunk, "the run ended first"
            seen += chunk
        proc.send_signal(signal.SIGINT)
        out, err = proc.communicate(timeout=30)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert proc.returncode == 130
    lines = [ln for ln in err.replace("\r", "\n").splitlines() if "interrupted" in ln]
    assert lines == ["python -m beltmdsm simulate: interrupted"], err
    assert "Traceback" not in err and "SystemError" not in err


# ------------------------------------------------------------ 4. Stribeck, small v_s


#: Runs the command line twice in one process: first with the cheap v_s (numba compiles
#: the Stribeck kernels: the compiler's peak, 700-880 MB, is not the run's), then, after
#: the kernel's peak-memory mark is reset (/proc/self/clear_refs, Linux), as given; prints
#: the second call's peak resident memory (VmHWM) in KiB.
_MEASURED = (
    "import sys; from beltmdsm.cli import main; "
    "argv = sys.argv[1:]; main([a if a != '1e-6' else '1e-1' for a in argv]); "
    "open('/proc/self/clear_refs', 'w').write('5'); rc = main(argv); "
    "hwm = [l for l in open('/proc/self/status') if l.startswith('VmHWM')][0]; "
    "print('maxrss', int(hwm.split()[1]), file=sys.stderr); sys.exit(rc)"
)


def test_stribeck_with_a_small_velocity_scale_stays_bounded():
    from beltmdsm.periodic.floquet import floquet

    # the report: 102 s and 7.1 GB (floquet); simulate's summary calls floquet (peak
    # memory of the run alone, `_MEASURED`)
    results = []
    for argv in (
        ["floquet", "--friction", "stribeck", "--v_s", "1e-6", "--json"],
        ["simulate", "--friction", "stribeck", "--v_s", "1e-6", "--t-end", "50", "--json"],
    ):
        out = subprocess.run(
            [sys.executable, "-W", "ignore", "-c", _MEASURED, *argv],
            capture_output=True,
            text=True,
            timeout=120,
            env=ENV,
            cwd=ROOT,
        )
        assert out.returncode == 0, out.stderr
        kib = int(out.stderr.split("maxrss")[-1])
        assert kib < 600 * 1024, kib  # 181 MB measured, against 7.1 GB
        results.append(json.loads(out.stdout.strip().splitlines()[-1]))
    # the same stick-slip response at v_s = 1e-3, where the full sliding guess is cheap:
    # the law differs only within 1e-3 m/s of Vr = 0, which the orbit crosses at switches
    # (numpy evaluates both slip directions' exp(+-(Vb - Y1) / v_s) before select picks
    # one: the other overflows to inf, unused; generated/hybrid.py silences divide and
    # invalid only)
    with np.errstate(over="ignore"):
        ref = floquet(Model(friction="stribeck", v_s=1e-3)).max_abs_multiplier
    assert results[0]["max_abs_multiplier"] == pytest.approx(ref, abs=1e-4)
    assert results[1]["status"] == "done"


# ------------------------------------------------------------ 5. unbounded requests


@pytest.mark.parametrize(
    "argv, flag",
    [
        (["simulate", "--omega1", "1e-200", "--t-end", "20"], "--omega1"),
        (["simulate", "--omega1", "1e-300", "--t-end", "20"], "--omega1"),
        (["simulate", "--omega2", "1e200", "--t-end", "20"], "--omega2"),
        (["floquet", "--omega1", "1e-200"], "--omega1"),
        (["coexistence", "--param", "Vb", "--from", "3", "--to", "5", "--step", "1e-6"], "--step"),
        (
            ["floquet-map", "--x", "Vb", "--x-from", "0.5", "--x-to", "12", "--y", "beta1"]
            + ["--y-from", "0.5", "--y-to", "2", "--rows", "1000000"],
            "--points/--rows",  # --rows is --points' other spelling (issue 37)
        ),
    ],
)
def test_unbounded_requests_are_refused_in_one_line(argv, flag):
    rc, out, err = _cli(*argv, timeout=60)
    line = _one_line(err)
    assert rc == 2 and out == ""
    assert f"argument {flag}:" in line


def test_a_non_finite_start_is_refused_naming_the_parameter():
    from beltmdsm.errors import Refused
    from beltmdsm.model import as_model
    from beltmdsm.settings import check_finite

    # X1 = mu_s g / omega1^2 (Eq. 9) overflows at omega1 = 1e-200, its square at 1e-150
    # (X1 = 3.9e200 at 1e-100: the energy balance's square overflows)
    for omega1 in (1e-200, 1e-150, 1e-100):
        with pytest.raises(Refused) as caught:
            check_finite(as_model(None, omega1=omega1, Vb=3.0))
        assert caught.value.names == ("omega1",)  # Vb is not to blame
    check_finite(as_model(None, omega1=1e-70))  # X1 = 3.9e140, its square finite


# ------------------------------------------------------------ 6. a failing point


def test_a_sweep_keeps_the_points_around_one_that_cannot_compute_all(tmp_path):
    argv = ["sweep", "--param", "Omega", "--values", "0.05", "1", "2", "3", "4", "5"]
    argv += ["--modulation", "--t-end", "100", "--jobs", "2", "--no-cache", "--json"]
    rc, out, err = _cli(*argv, timeout=300)
    assert rc == 0, err
    rows = {r["Omega"]: r for r in json.loads(out)["rows"]}
    assert sorted(rows) == [0.05, 1, 2, 3, 4, 5]
    slow = rows[0.05]
    # 2 pi / 0.05 = 125.7 s is longer than the steady window, which starts at
    # 0.3 t_end = 30 s (not at 125.7 s, as the message said)
    # NaN, written null in JSON
    assert all(slow[f"mu_eff_Omega_{s}"] is None for s in ("mean", "std", "range"))
    assert "no full cycle of 125.664 s" in slow["error"] and "t = 30 s" in slow["error"]
    # sliding back throughout under Coulomb friction: mu_eff = mu_s = 0.4 exactly
    assert slow["regime"] == "continuous_sliding"
    assert slow["mu_eff_omega1_mean"] == pytest.approx(0.4, rel=1e-9)
    assert all(rows[v]["error"] == "" and rows[v]["status"] == "done" for v in (1, 2, 3, 4, 5))


def test_simulate_keeps_its_run_and_says_what_it_could_not_compute():
    rc, out, err = _cli("simulate", "--Omega", "0.05", "--modulation", "--t-end", "100")
    assert rc == 0, err
    assert "status: done" in out
    assert "not computed: mu_eff over 2pi/Omega: no full cycle of 125.664 s" in out
    assert "over 2pi/omega1: 0.4 +-" in out


def test_a_point_whose_run_fails_is_a_row_that_says_why(monkeypatch):
    from beltmdsm.batch import row, sweep
    from beltmdsm.errors import StepTooSmall
    from beltmdsm.settings import SolverSettings

    real = row.simulate

    def failing(model, **kw):
        if model["Vb"] == 3.0:
            raise StepTooSmall("the step fell below the rounding of the time", 1e-10, 1e-10)
        return real(model, **kw)

    monkeypatch.setattr(row, "simulate", failing)
    settings = SolverSettings(t_end=40.0)
    result = sweep.sweep(
        None,
        "Vb",
        [2.0, 3.0, 4.0],
        settings=settings,
        executor="serial",
        cache_dir=None,
        progress=False,
    )
    t = result.table
    assert list(t["status"]) == ["done", "failed", "done"]
    assert t["error"][1].startswith("StepTooSmall: the step fell below")
    assert not t["resolved"][1] and not t["omega1_peak_present"][1]
    assert t["error"][0] == t["error"][2] == ""
    # the other points are the runs they would be alone
    alone = real(result.model.replace(Vb=4.0), settings=settings).summary
    assert t["n_switches"][2] == alone.n_switches


# ------------------------------------------------------------ 7. divide by zero


def _band(*argv):
    rc, out, err = _cli("floquet-band", *argv, "--json", "--no-progress", timeout=150)
    assert rc == 0, err
    return json.loads(out)


def test_floquet_band_edges_where_the_secant_had_no_slope():
    from beltmdsm.periodic.floquet import floquet

    band = _band("--param", "Vb", "--from", "0.5", "--to", "12", "--beta1", "1.5")
    doubling = [e for e in band["edges"] if e["kind"] == "period_doubling"]
    assert len(doubling) == 1
    edge = doubling[0]
    assert edge["unstable_above"] and edge["accuracy"] <= 1e-6
    # independent: floquet on both sides of the edge, max |mu| crosses 1 there
    below = floquet(Model(beta1=1.5, Vb=edge["value"] - 1e-4)).max_abs_multiplier
    above = floquet(Model(beta1=1.5, Vb=edge["value"] + 1e-4)).max_abs_multiplier
    assert below < 1.0 < above
    band = _band("--param", "beta1", "--from", "0", "--to", "2")
    assert band["edges"]


@pytest.mark.slow
def test_floquet_map_over_beta1_runs():
    argv = ["floquet-map", "--x", "Vb", "--x-from", "0.5", "--x-to", "12", "--y", "beta1"]
    argv += ["--y-from", "0.5", "--y-to", "2", "--rows", "10", "--json", "--no-progress"]
    rc, out, err = _cli(*argv, timeout=600)
    assert rc == 0 and "ZeroDivisionError" not in err, err
    assert json.loads(out)["curves"]
