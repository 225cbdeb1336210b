"""A command line that starts at once (issue 18): what starting imports.

``import beltmdsm`` and ``beltmdsm --help`` (and every command's ``--help``) import no
heavy package; a run imports what it runs and not what other commands need (SciPy's
integrators, optimizers and signal processing, matplotlib, SymPy, mpmath). Each case runs
in a fresh interpreter and lists the modules loaded at its end. The times themselves are
measured by benchmarks/bench_start.py (a test on a shared machine cannot time them
reliably).
"""

import json
import subprocess
import sys
from pathlib import Path

import pytest

from beltmdsm.cli import COMMANDS

ROOT = Path(__file__).resolve().parents[3]

#: Imported by neither ``import beltmdsm`` nor any ``--help``.
HEAVY = ("scipy", "matplotlib", "numba", "llvmlite", "tqdm", "sympy", "mpmath", "dask")
#: Not imported by a run of ``simulate`` or ``sweep``: what other commands need, and
#: SciPy's integrators (0.3 s to import; the package integrates with its own DOP853,
#: the normal orbit of a run's Floquet check included).
NOT_FOR_A_RUN = (
    "scipy.integrate",
    "scipy.optimize",
    "scipy.signal",
    "scipy.spatial",
    "matplotlib",
    "sympy",
    "mpmath",
    "dask",
)

_LOADED = """
import io, json, runpy, sys, contextlib
argv = json.loads(sys.argv[1])
if argv is None:
    import beltmdsm
else:
    sys.argv = ["beltmdsm", *argv]
    with contextlib.redirect_stdout(io.StringIO()):
        try:
            runpy.run_module("beltmdsm", run_name="__main__")
        except SystemExit as e:
            assert e.code in (0, None), e.code
print(json.dumps(sorted(sys.modules)))
"""


def loaded(argv):
    """The modules loaded by ``python -m beltmdsm ARGV`` (``None``: ``import beltmdsm``)."""
    r = subprocess.run(
        [sys.executable, "-c", _LOADED, json.dumps(argv)],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout.strip().splitlines()[-1])


def offending(modules, packages):
    return sorted(m for m in modules if any(m == p or m.startswith(p + ".") for p in packages))


@pytest.mark.parametrize("argv", [None, ["--help"]], ids=["import", "help"])
def test_starting_imports_no_heavy_package(argv):
    assert offending(loaded(argv), HEAVY) == []


def test_no_command_help_imports_a_heavy_package():
    code = (
        "import contextlib, io, json, sys\n"
        "from beltmdsm.cli import COMMANDS, main\n"
        "for name in COMMANDS:\n"
        "    with contextlib.redirect_stdout(io.StringIO()):\n"
        "        try:\n"
        "            main([name, '--help'])\n"
        "        except SystemExit:\n"
        "            pass\n"
        "print(json.dumps(sorted(sys.modules)))\n"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT)
    assert r.returncode == 0, r.stderr
    assert offending(json.loads(r.stdout.strip().splitlines()[-1]), HEAVY) == []
    assert {"simulate", "sweep", "floquet", "predict", "validate"} <= set(COMMANDS)


@pytest.mark.parametrize(
    "argv",
    [
        ["simulate", "--Vb", "4", "--t-end", "20", "--no-progress"],
        [
            "sweep",
            *("--param", "Vb", "--from", "1", "--to", "2", "--step", "1", "--t-end", "20"),
            *("--no-cache", "--no-progress", "--jobs", "1"),
        ],
        # a peak checked against the Floquet rate of the periodic response: the normal
        # orbit and the period map are computed
        ["simulate", "--Vb", "3.5", "--t-end", "1000", "--no-progress"],
    ],
    ids=["simulate", "sweep", "simulate-with-floquet-check"],
)
def test_a_run_imports_only_what_it_runs(argv):
    modules = loaded(argv)
    assert offending(modules, NOT_FOR_A_RUN) == []
    if "3.5" in argv:
        assert "beltmdsm.periodic.closed_form" in modules
