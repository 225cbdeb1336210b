"""Sweeps on a real dask.distributed cluster: a scheduler and two worker processes.

`tests/beltmdsm/batch/test_sweep.py` runs a sweep on an in-process dask client; here the
sweep goes through ``python -m beltmdsm sweep --scheduler tcp://127.0.0.1:PORT`` to a ``dask
scheduler`` and two ``dask worker`` processes on this machine, as it would to a
cluster, once undisturbed and once with a worker killed (SIGKILL) in the middle.
Marked slow (starting the processes takes seconds): ``python -m pytest -m slow
tests/beltmdsm/batch/test_dask_cluster.py``.
"""

import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

distributed = pytest.importorskip("distributed")

from beltmdsm.batch.cache import identity, read_cached  # noqa: E402
from beltmdsm.batch.row import columns  # noqa: E402
from beltmdsm.batch.sweep import sweep  # noqa: E402
from beltmdsm.model import Model  # noqa: E402
from beltmdsm.settings import SolverSettings  # noqa: E402

pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[3]
NUMERIC = (
    "peak_omega1",
    "omega1_peak_at",
    "peak_Omega",
    "energy_residual",
    "n_switches",
    "n_reversals",
    "mean_friction",
    "min_normal_force",
    "vr_min",
    "vr_max",
)


def _dask():
    exe = shutil.which("dask", path=str(Path(sys.executable).parent)) or shutil.which("dask")
    if exe is None:
        pytest.skip("the dask command is not installed")
    return exe


def _free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _env():
    # the workers unpickle beltmdsm.batch.sweep._cached_run: they must import this checkout
    path = os.environ.get("PYTHONPATH")
    return {
        **os.environ,
        "PYTHONPATH": str(ROOT) + (os.pathsep + path if path else ""),
        "PYTHONDONTWRITEBYTECODE": "1",
    }


@pytest.fixture
def cluster():
    """``(address, workers)``: a scheduler and two single-threaded workers, stopped after."""
    dask = _dask()
    address = f"tcp://127.0.0.1:{_free_port()}"
    procs = []

    def start(*args):
        procs.append(
            subprocess.Popen(
                [dask, *args],
                cwd=ROOT,
                env=_env(),
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
            )
        )
        return procs[-1]

    try:
        start(
            "scheduler",
            "--host",
            "127.0.0.1",
            "--port",
            address.rsplit(":", 1)[1],
            "--no-dashboard",
        )
        # --no-nanny: the worker is the process itself, so killing it kills the worker
        # (a nanny would restart it)
        workers = [
            start(
                "worker",
                address,
                "--nworkers",
                "1",
                "--nthreads",
                "1",
                "--no-dashboard",
                "--no-nanny",
                "--host",
                "127.0.0.1",
            )
            for _ in range(2)
        ]
        with distributed.Client(address, timeout="60s") as client:
            client.wait_for_workers(2, timeout=120)
        yield address, workers
    finally:
        # workers first: a worker that loses its scheduler retries for a while
        for p in reversed(procs):
            if p.poll() is None:
                p.terminate()
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()


def _cli_sweep(address, values, t_end, cache_dir=None):
    argv = [
        sys.executable,
        "-m",
        "derive",
        "sweep",
        "--param",
        "Vb",
        "--values",
        *map(str, values),
        "--t-end",
        str(t_end),
        "--scheduler",
        address,
        "--json",
        "--no-progress",
    ]
    argv += ["--cache-dir", str(cache_dir)] if cache_dir else ["--no-cache"]
    return subprocess.Popen(
        argv, cwd=ROOT, env=_env(), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )


def _assert_same_as_serial(rows, values, t_end):
    serial = sweep(
        None,
        "Vb",
        values,
        settings=SolverSettings(t_end=t_end),
        executor="serial",
        cache_dir=None,
        progress=False,
    ).table
    assert [r["Vb"] for r in rows] == list(values)
    assert [r["regime"] for r in rows] == list(serial["regime"])
    for name in NUMERIC:
        np.testing.assert_array_equal([r[name] for r in rows], serial[name], err_msg=name)


def test_sweep_on_a_dask_cluster_equals_the_serial_sweep(cluster):
    address, _ = cluster
    values, t_end = [2.0, 4.0, 6.0, 12.0], 40.0
    proc = _cli_sweep(address, values, t_end)
    out, err = proc.communicate(timeout=300)
    assert proc.returncode == 0, err
    _assert_same_as_serial(json.loads(out)["rows"], values, t_end)


def test_a_worker_killed_mid_sweep_loses_no_point_and_no_cache_file(cluster, tmp_path):
    address, workers = cluster
    values, t_end = [0.5 * k for k in range(1, 15)], 100.0
    proc = _cli_sweep(address, values, t_end, cache_dir=tmp_path)
    deadline = time.monotonic() + 240
    while len(list(tmp_path.glob("*.json"))) < 2:
        assert proc.poll() is None, proc.communicate()[1]
        assert time.monotonic() < deadline, "no point finished"
        time.sleep(0.05)
    done_at_kill = len(list(tmp_path.glob("*.json")))
    workers[0].send_signal(signal.SIGKILL)
    workers[0].wait(timeout=30)
    assert done_at_kill < len(values)  # the kill came in the middle
    out, err = proc.communicate(timeout=300)
    assert proc.returncode == 0, err
    _assert_same_as_serial(json.loads(out)["rows"], values, t_end)
    files = sorted(tmp_path.glob("*.json"))
    assert len(files) == len(values)
    settings = SolverSettings(t_end=t_end)
    for path in files:
        vb = json.loads(path.read_text())["params"]["Vb"]
        ident = identity(Model(Vb=vb), settings)
        row, problem = read_cached(path, ident, [name for name, _ in columns(False)])
        assert problem is None and row is not None, (path, problem)
