"""The suite on two cores (pytest-xdist, tests/conftest.py): the `EARLY` work starts once
per run, on the worker whose tests read it; the tests that share a fixture outliving
one test run on one worker; a run of files stays in one process.

The run below is a small suite of its own in a temporary folder with this suite's
conftest: a fixture like `derivations` whose start function leaves a line in a file
(its worker, and whether it started at collection) and starts a process that the
stop function ends."""

import os
import subprocess
import sys
import textwrap
from pathlib import Path
from types import SimpleNamespace

import conftest
import pytest

ROOT = Path(__file__).resolve().parents[1]

#: A test module with an `EARLY` fixture (`derivations`), read by four tests, beside
#: twenty that read nothing and a module fixture read by two.
MODULE = """
import os
import subprocess
import sys
from pathlib import Path

import pytest

LOG = Path(os.environ["EARLY_LOG"])
STARTED = {}


def start_derivations(folder):
    proc = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(600)"])
    worker = os.environ.get("PYTEST_XDIST_WORKER", "main")
    with LOG.open("a") as log:
        log.write(f"start {worker} {proc.pid} {os.environ.get('PYTEST_CURRENT_TEST') is None}\\n")
    return proc


def stop_derivations(proc):
    proc.kill()
    proc.wait()


@pytest.fixture(scope="module")
def derivations(tmp_path_factory):
    proc = STARTED.pop("derivations", None) or start_derivations(tmp_path_factory.mktemp("d"))
    yield proc.pid
    stop_derivations(proc)


@pytest.fixture(scope="module")
def shared():
    with LOG.open("a") as log:
        log.write(f"shared {os.environ.get('PYTEST_XDIST_WORKER', 'main')}\\n")
    return 1


@pytest.mark.parametrize("i", range(4))
def test_reads(derivations, i):
    assert derivations > 0


@pytest.mark.parametrize("i", range(20))
def test_alone(i):
    assert i >= 0


@pytest.mark.parametrize("i", range(2))
def test_shared(shared, i):
    assert shared == 1
"""


def _run(tmp_path, *args):
    """Run the small suite with ``args``; its exit status and the lines of its log."""
    suite = tmp_path / "suite"
    suite.mkdir()
    (suite / "conftest.py").write_text((ROOT / "tests" / "conftest.py").read_text())
    (suite / "test_early.py").write_text(textwrap.dedent(MODULE))
    log = tmp_path / "early.log"
    # not this run's PYTEST_CURRENT_TEST, PYTEST_XDIST_WORKER, ...: the log reads them
    env = {k: v for k, v in os.environ.items() if not k.startswith("PYTEST_")}
    env.update(EARLY_LOG=str(log), PYTHONPATH=str(ROOT))
    done = subprocess.run(
        [sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "-q", *args, str(suite)],
        cwd=tmp_path, env=env, capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    lines = log.read_text().splitlines() if log.exists() else []
    return done, lines


def _alive(pid):
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except (FileNotFoundError, ProcessLookupError):
        return False
    return stat.rsplit(")", 1)[1].split()[0] != "Z"


@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="reads Linux's /proc")
def test_two_workers_start_the_early_work_once_where_its_tests_run(tmp_path):
    pytest.importorskip("xdist")
    done, lines = _run(tmp_path, "-n", "2", "--dist", "loadgroup", "--no-loadscope-reorder")
    assert done.returncode == 0, done.stdout + done.stderr
    assert "26 passed" in done.stdout, done.stdout
    starts = [line.split() for line in lines if line.startswith("start")]
    shared = [line for line in lines if line.startswith("shared")]
    assert len(starts) == 1 and len(shared) == 1, lines  # once per run, not per worker
    assert starts[0][1].startswith("gw"), lines  # in the worker that ran its tests
    assert not _alive(int(starts[0][2]))  # and stopped when they were done


@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="reads Linux's /proc")
def test_one_process_starts_it_at_collection_and_stops_it(tmp_path):
    done, lines = _run(tmp_path, "-n", "0")
    assert done.returncode == 0, done.stdout + done.stderr
    assert "26 passed" in done.stdout, done.stdout
    starts = [line.split() for line in lines if line.startswith("start")]
    # at collection, before any test ran: beside the tests, not after them
    assert len(starts) == 1 and starts[0][1] == "main" and starts[0][3] == "True", lines
    assert not _alive(int(starts[0][2]))


@pytest.mark.parametrize(
    "args, parallel",
    [
        (["tests"], True),
        ([], True),  # pytest's args are testpaths then
        (["tests/beltmdsm/cli"], True),
        (["tests/test_layers.py"], False),
        (["tests/test_layers.py::test_no_import_cycle", "notebooks/fig05_floquet.ipynb"], False),
    ],
)
def test_auto_is_a_worker_per_core_for_folders_and_none_for_files(args, parallel, monkeypatch):
    monkeypatch.delenv("PYTEST_XDIST_AUTO_NUM_WORKERS", raising=False)
    config = SimpleNamespace(
        invocation_params=SimpleNamespace(dir=ROOT), args=args or ["tests", "notebooks"]
    )
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    expected = min(cores, 8) if parallel and cores > 1 else 0
    assert conftest.pytest_xdist_auto_num_workers(config) == expected
    monkeypatch.setenv("PYTEST_XDIST_AUTO_NUM_WORKERS", "3")
    assert conftest.pytest_xdist_auto_num_workers(config) == 3


def test_the_tests_handed_out_first_exist():
    """`conftest.FIRST` names files of this checkout: a renamed one would silently go
    back to its place in the order, and the run's tail would grow."""
    for prefix in conftest.FIRST:
        assert (ROOT / prefix.split("::")[0]).is_file(), prefix
