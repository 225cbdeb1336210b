"""Ctrl-C and ``kill -9`` through the command line (issue 36 items 3, 12, 13): a command
interrupted on a dask cluster stops at once, keeping what finished, and a command
killed leaves no process of its own behind.

The dask tests start a scheduler and a worker process on 127.0.0.1 in the test (a
``LocalCluster``) and are marked slow (the basins map seeds its attractors for about
30 s first): ``python -m pytest -m slow tests/beltmdsm/cli/test_interrupts_and_orphans.py``.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]
ENV = {**os.environ, "PYTHONPATH": str(ROOT)}
#: What the reports measured before (issue 36): a dask basins map went on for 308 s after
#: Ctrl-C, a sweep 10.6 s; the workers of a killed sweep were alive after 60 s. The
#: bounds below leave room for a busy 2-core machine (the measured times are in the
#: commit messages), and still fail the old behaviour.
STOP_S = 10.0
ORPHAN_S = 10.0


def _start(argv, **kw):
    return subprocess.Popen(
        [sys.executable, "-m", "beltmdsm", *argv],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=ENV,
        cwd=ROOT,
        start_new_session=True,  # its own process group, as a terminal's Ctrl-C sees it
        **kw,
    )


def _wait_for_files(proc, folder, n=1, limit=240):
    deadline = time.monotonic() + limit
    while len(list(folder.glob("*.json"))) < n:
        assert proc.poll() is None, proc.communicate()[1]
        assert time.monotonic() < deadline, "nothing finished"
        time.sleep(0.05)


def _interrupt(proc):
    """Ctrl-C to the command's process group; ``(seconds to its exit, stdout, stderr)``."""
    os.killpg(proc.pid, signal.SIGINT)
    sent = time.monotonic()
    try:
        out, err = proc.communicate(timeout=600)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    return time.monotonic() - sent, out, err


def _alive(pid):
    """Whether process ``pid`` runs (a zombie, dead but not yet reaped, does not)."""
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except (FileNotFoundError, ProcessLookupError):
        return False
    return stat.rsplit(")", 1)[1].split()[0] != "Z"


def _children(pid):
    """The pids of the processes whose parent is ``pid`` (Linux's /proc)."""
    out = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[1]) == pid:
            out.append(int(stat.parent.name))
    return out


@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="reads Linux's /proc")
def test_the_workers_of_a_killed_sweep_end_with_it(tmp_path):
    """Issue 36 item 13: ``kill -9`` of a ``sweep --jobs 2`` parent left its two workers
    running (parent 1, 225 MB each) after 60 s; they end with it now."""
    argv = ["sweep", "--param", "Vb", "--values", *map(str, range(1, 9)), "--t-end", "1500"]
    proc = _start([*argv, "--jobs", "2", "--cache-dir", str(tmp_path), "--no-progress"])
    workers = []
    try:
        _wait_for_files(proc, tmp_path)  # the workers are busy with the other points
        workers = _children(proc.pid)
        assert len(workers) >= 2, workers
        proc.kill()
        proc.wait()
        killed = time.monotonic()
        while any(map(_alive, workers)) and time.monotonic() - killed < ORPHAN_S:
            time.sleep(0.05)
        left = [pid for pid in workers if _alive(pid)]
    finally:
        for pid in [*_children(proc.pid), *workers]:
            if _alive(pid):
                os.kill(pid, signal.SIGKILL)
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert left == [], f"workers still running {ORPHAN_S} s after their parent was killed"


@pytest.fixture(scope="module")
def cluster():
    """The address of a dask scheduler with one worker process, on 127.0.0.1."""
    distributed = pytest.importorskip("distributed")
    # the worker imports this checkout (the starts and points are its functions)
    os.environ["PYTHONPATH"] = ENV["PYTHONPATH"]
    with distributed.LocalCluster(
        n_workers=1,
        threads_per_worker=2,
        processes=True,
        host="127.0.0.1",
        dashboard_address=None,
    ) as local:
        yield local.scheduler_address


@pytest.mark.slow
def test_ctrl_c_stops_basins_on_a_dask_cluster_at_once_and_says_what_it_kept(cluster, tmp_path):
    """Issue 36 items 3 and 12: ``basins --scheduler`` went on for 308 s after Ctrl-C
    (the executor's shutdown waited for the whole round) and said only "interrupted"."""
    argv = ["basins", "--Vb", "3.88", "--points", "200", "--scheduler", cluster]
    proc = _start([*argv, "--cache-dir", str(tmp_path)])
    _wait_for_files(proc, tmp_path, n=4)
    stopped, out, err = _interrupt(proc)
    assert proc.returncode == 130 and out == ""
    assert stopped < STOP_S, f"{stopped:.1f} s from Ctrl-C to the end"
    (line,) = [ln for ln in err.splitlines() if "interrupted" in ln]
    assert "every start finished is kept in the cache" in line and str(tmp_path) in line
    received = int(line.split("stopped after ")[1].split(" of ")[0])
    kept = list(tmp_path.glob("*.json"))
    # the cache holds every start this process received (a worker writes it first)
    assert 4 <= len(kept) < 200 * 200 and received <= len(kept)
    for path in kept:
        assert "label" in json.loads(path.read_text())["row"]


@pytest.mark.slow
def test_ctrl_c_stops_a_sweep_on_a_dask_cluster_at_once(cluster, tmp_path):
    argv = ["sweep", "--param", "Vb", "--values", *map(str, range(1, 13)), "--t-end", "1500"]
    proc = _start([*argv, "--scheduler", cluster, "--cache-dir", str(tmp_path), "--no-progress"])
    _wait_for_files(proc, tmp_path)
    stopped, out, err = _interrupt(proc)
    assert proc.returncode == 130 and out == ""
    assert stopped < STOP_S, f"{stopped:.1f} s from Ctrl-C to the end"
    assert "every point finished is kept in the cache" in err
