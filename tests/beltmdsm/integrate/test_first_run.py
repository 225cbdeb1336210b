"""The first run (issue 30 item 7): a process that finds the compiled integrators not
cached runs them as plain Python while a child compiles them, says so once, and gives
the numbers a compiled run gives; a compile in the foreground is said once and left out
of the progress bar's clock (`beltmdsm.integrate._background`).

No test here times anything: benchmarks/bench_start.py measures the cold and warm runs.
"""

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from beltmdsm import simulate
from beltmdsm.integrate import _background
from beltmdsm.model import Model

ROOT = Path(__file__).resolve().parents[3]

NOTICE = "beltmdsm: compiling the integrator kernels once"


def _fresh(tmp_path):
    """The environment of a new installation: empty numba and package caches."""
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    env.update(NUMBA_CACHE_DIR=str(tmp_path / "numba"), BELTMDSM_CACHE=str(tmp_path / "cache"))
    return env


def _run(code, env, timeout=600):
    done = subprocess.run(
        [sys.executable, "-c", code],
        env=env,
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=timeout,
    )
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.splitlines()[-1]), done.stderr


#: Two runs in one process; what it imported and whether it handed compiles to a child.
_TWO_RUNS = """
import json, sys
import numpy as np
from beltmdsm import Model, simulate
from beltmdsm.integrate import _background
runs = [simulate(Model(Vb=4.0), t_end=8.0, t_discard=2.0) for _ in range(2)]
child = _background._child[0] if _background._child else None
if child is not None and {stop_child}:
    child.kill()  # the compile itself is not this test's (the slow test waits for it)
    child.wait()
elif child is not None:
    child.stdin.close()  # what the end of the process does: the child finishes its jobs
    child.wait()
print(json.dumps({{
    "y": runs[0].y.tolist(),
    "same": bool(np.array_equal(runs[0].y, runs[1].y)),
    "numba": "numba" in sys.modules,
    "child": child is not None,
}}))
"""


def test_a_cold_process_runs_plain_python_says_so_once_and_hands_the_compile_on(tmp_path):
    got, err = _run(_TWO_RUNS.format(stop_child=True), _fresh(tmp_path))
    # the compile went to the child: this process did not even import numba
    assert got["child"] and not got["numba"]
    assert [line for line in err.splitlines() if NOTICE in line] == [
        f"{NOTICE}, in the background (~{_background.ABOUT_S} s; cached in "
        f"{tmp_path / 'numba'}); this run uses them as plain Python meanwhile (same results)"
    ]
    # the plain-Python integrators' numbers, in both runs (the compiled ones agree with
    # them: test_superposition.py::test_compiled_and_python_scans_agree)
    ref = simulate(Model(Vb=4.0), t_end=8.0, t_discard=2.0, backend="python")
    np.testing.assert_array_equal(np.array(got["y"]), ref.y)
    assert got["same"]


@pytest.mark.slow
def test_after_the_child_the_next_process_is_compiled_and_says_nothing(tmp_path):
    # the child compiles the kernels (about 15 s of one core, more on a busy machine)
    env = _fresh(tmp_path)
    cold, err = _run(_TWO_RUNS.format(stop_child=False), env)
    assert cold["child"] and sum(NOTICE in line for line in err.splitlines()) == 1
    ready = sorted(p.name for p in (tmp_path / "numba" / "beltmdsm-ready").iterdir())
    assert {"advance", "evaluate"} <= {name.split("_")[1] for name in ready}
    warm, err = _run(_TWO_RUNS.format(stop_child=True), env)
    assert warm["numba"] and not warm["child"] and NOTICE not in err
    assert warm["y"] == cold["y"]


@pytest.mark.slow
def test_a_compile_asked_for_is_done_at_once_and_said_once(tmp_path):
    code = (
        "import json, sys\n"
        "from beltmdsm import Model, simulate\n"
        "from beltmdsm.integrate import _background\n"
        "for _ in range(2):\n"
        "    simulate(Model(Vb=4.0), t_end=8.0, t_discard=2.0, backend='numba')\n"
        "print(json.dumps({'child': bool(_background._child),"
        " 'made': _background.compile_seconds() > 0}))\n"
    )
    env = _fresh(tmp_path)
    got, err = _run(code, env)
    assert got == {"child": False, "made": True}
    assert [line for line in err.splitlines() if NOTICE in line] == [
        f"{NOTICE} (~{_background.ABOUT_S} s; cached in {tmp_path / 'numba'})"
    ]
    got, err = _run(code, env)  # cached: loaded, nothing said
    assert got == {"child": False, "made": True} and NOTICE not in err


def test_a_lazy_function_runs_python_until_the_child_marks_it_ready(monkeypatch, tmp_path):
    numba = pytest.importorskip("numba")
    monkeypatch.setattr(_background, "_numba_cache", lambda: str(tmp_path))
    # as in a process that has not asked for compiled code at once (an earlier test of
    # this worker with backend="numba" did: then everything compiles at once)
    monkeypatch.setattr(_background, "_eager", [False])
    jobs = []
    monkeypatch.setattr(_background, "_submit", lambda *job: jobs.append(job) or True)

    def python(x):
        return ("python", x)

    stem = f"test_lazy_{os.getpid()}"
    spec = (lambda: numba.njit(lambda x: x + 1.0), ())
    lazy = _background.Lazy(spec, stem, python)
    assert lazy(1.0) == ("python", 1.0) and lazy(2.0) == ("python", 2.0)
    assert len(jobs) == 1 and jobs[0][1] == stem  # handed on once
    _background._mark(stem)  # what the child does once the code is in numba's cache
    assert lazy(1.0) == 2.0 and lazy.fn is not None and len(jobs) == 1


@pytest.mark.parametrize(
    "value",
    [
        1.5,
        3,
        True,
        (1.0, 2.0, 3.0),
        np.zeros(3),
        np.zeros((3, 4)),
        np.zeros((3, 4), order="F"),
        np.zeros((4, 6))[::2, ::3],
        np.zeros(5, dtype=np.int64),
        np.broadcast_to(np.zeros(3), (2, 3)),
    ],
    ids=["float", "int", "bool", "tuple", "1d", "2d C", "2d F", "strided", "int64", "readonly"],
)
def test_the_child_compiles_for_the_types_of_the_call(value):
    """What is sent to the child stands for each argument by what numba types it by
    (not its data): the child compiles the signature the run then calls."""
    numba = pytest.importorskip("numba")
    assert numba.typeof(_background._standin(_background._describe(value))) == numba.typeof(value)


def test_the_progress_bar_leaves_the_compile_out(monkeypatch):
    """The bar's clock stops for what the compile took: a run whose compile took 1000 s
    (a fake clock) shows none of it; a run that itself took 1000 s shows it all."""
    import tqdm
    import tqdm.std

    clock = {}
    monkeypatch.setattr(tqdm.std, "time", lambda: clock["t"])
    bars = []

    class Kept(tqdm.tqdm):
        def __init__(self, *a, **k):
            super().__init__(*a, **k)
            bars.append(self)

    monkeypatch.setattr(tqdm, "tqdm", Kept)

    def made():
        clock["calls"] += 1
        if clock["calls"] == 2:  # by the end of the run's first segment
            clock["t"] = 1000.0
            if clock["compiling"]:
                clock["made"] = 1000.0  # the 1000 s went to the compile
        return clock["made"]

    monkeypatch.setattr(_background, "compile_seconds", made)
    for compiling, elapsed in ((True, 0.0), (False, 1000.0)):
        clock.update(t=0.0, made=0.0, calls=0, compiling=compiling)
        simulate(Model(Vb=4.0), t_end=8.0, t_discard=2.0, progress=True, backend="python")
        assert clock["calls"] > 2 and bars[-1].format_dict["elapsed"] == elapsed


# ------------------------------------------- no process outlives its command (issue 37)


def _compile_child(proc, limit=120):
    """The pid of the child compiling for ``proc`` (Linux's /proc), once it has started."""
    deadline = time.monotonic() + limit
    while time.monotonic() < deadline:
        assert proc.poll() is None, proc.communicate()
        for stat in Path("/proc").glob("[0-9]*/stat"):
            try:
                ppid = int(stat.read_text().rsplit(")", 1)[1].split()[1])
                cmd = (stat.parent / "cmdline").read_bytes()
            except (OSError, ValueError):
                continue
            if ppid == proc.pid and b"_serve" in cmd:
                return int(stat.parent.name)
        time.sleep(0.05)
    raise AssertionError("no compile child started")


def _alive(pid):
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def _gone_within(pid, seconds):
    deadline = time.monotonic() + seconds
    while _alive(pid) and time.monotonic() < deadline:
        time.sleep(0.05)
    alive = _alive(pid)
    if alive:
        os.kill(pid, signal.SIGKILL)
    return not alive


#: A cold command that runs long enough to be stopped while its child compiles.
_LONG = [sys.executable, "-m", "beltmdsm", "simulate", "--Vb", "4", "--t-end", "3000"]


@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="reads Linux's /proc")
@pytest.mark.parametrize("how", ["kill -9", "Ctrl-C"])
def test_a_command_stopped_while_its_child_compiles_takes_the_child_with_it(tmp_path, how):
    """Issue 37 item 1: a cold first run left an orphaned compile (parent 1) running
    about 45 s after the command had returned."""
    proc = subprocess.Popen(
        _LONG,
        env=_fresh(tmp_path),
        cwd=ROOT,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    try:
        child = _compile_child(proc)
        if how == "kill -9":
            proc.kill()
        else:
            os.killpg(proc.pid, signal.SIGINT)
        _, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert _gone_within(child, 10.0), f"the compile outlived its command ({how})"
    if how == "Ctrl-C":
        assert proc.returncode == 130 and "waiting" not in err
    # its claim on the compile is released: the next run may compile at once
    assert not list((tmp_path / "numba").rglob("*.compiling"))


@pytest.mark.slow
def test_a_cold_command_waits_for_its_compile_says_so_once_and_leaves_nothing(tmp_path):
    env = _fresh(tmp_path)
    argv = [sys.executable, "-m", "beltmdsm", "simulate", "--Vb", "4", "--t-end", "8"]
    proc = subprocess.Popen(
        argv, env=env, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    child = _compile_child(proc)
    _, err = proc.communicate(timeout=600)
    assert proc.returncode == 0, err
    assert not _alive(child)  # it ended before its command did
    waits = [line for line in err.splitlines() if "waiting for the compile" in line]
    assert len(waits) == 1 and "Ctrl-C stops it" in waits[0]
    warm = subprocess.run(argv, env=env, cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert warm.returncode == 0 and warm.stderr == "", warm.stderr
