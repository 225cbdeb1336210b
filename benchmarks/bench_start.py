"""Start-up and whole-process speed of the command line, as ratios from one run.

Every figure is a whole process, timed from outside (the median of ``--repeat`` runs,
after one run not counted, the two commands of a ratio taken in turn so that a
drift of the machine's speed falls on both):

1. ``beltmdsm --help`` (``python -m beltmdsm --help``) against ``python -c pass``, the
   interpreter's own start (target: the help under 0.5 s);
2. ``import beltmdsm`` against ``import numpy, scipy.integrate`` (target: at most 1.5x);
3. a 32-point sweep, ``python -m beltmdsm sweep --param Vb --from 0.5 --to 16 --step 0.5
   --jobs 1`` of 1000 s runs at the fast tolerance of benchmarks/bench_simulation.py
   (``--rtol 1e-7 --atol 1e-7``, without the cache), against the named baseline of
   that benchmark, plain ``solve_ivp(RK45, rtol=1e-9)`` with a right-hand side using
   ``np.sign`` (`benchmarks.bench_simulation.baseline`), run on the same points in a
   process of its own (target: at least 25x).

4. the first run of a new installation (issue 30 item 7), cold beside warm: ``simulate
   --t-end 50`` (target: within 3 s) and ``floquet`` (target: within 5 s) each in a
   process with fresh, empty caches (``NUMBA_CACHE_DIR`` and ``BELTMDSM_CACHE`` in a new
   temporary folder; the compile that such a process hands to a child process,
   `beltmdsm.integrate._background`, is stopped when it ends: it is not the run's),
   and the same commands with the caches filled; and the sweep of 3. from fresh caches
   against the same baseline.

numba compiles the integrators once and caches them on disk: before the warm figures,
one process compiles them in the foreground (``backend="numba"``) for the laws the
commands use, and a first sweep, not counted, runs. The package is byte-compiled
first, as an installation is (pip compiles what it installs): in a checkout run with
``PYTHONDONTWRITEBYTECODE`` set, every process would compile every module again.

Usage: python -m benchmarks.bench_start [--quick] [--repeat N]
"""

from __future__ import annotations

import argparse
import compileall
import os
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _sweep_command(points, t_end):
    stop = 0.5 * points
    return [
        sys.executable,
        "-m",
        "beltmdsm",
        "sweep",
        "--param",
        "Vb",
        "--from",
        "0.5",
        "--to",
        f"{stop:g}",
        "--step",
        "0.5",
        "--t-end",
        f"{t_end:g}",
        "--jobs",
        "1",
        "--rtol",
        "1e-7",
        "--atol",
        "1e-7",
        "--no-cache",
        "--no-progress",
    ]


def _baseline_command(points, t_end):
    code = (
        "from benchmarks.bench_simulation import baseline\n"
        f"for k in range(1, {points} + 1):\n"
        f"    baseline(0.5 * k, {t_end!r}, 0.02, {0.3 * t_end!r})\n"
    )
    return [sys.executable, "-c", code]


def _wall(command, env=None):
    start = time.perf_counter()
    subprocess.run(command, cwd=ROOT, check=True, capture_output=True, env=env)
    return time.perf_counter() - start


#: The first-run commands: a 50 s simulation (with its summary's Floquet check) and the
#: periodic response with its multipliers, at the base parameters.
FIRST_RUNS = {
    "simulate --t-end 50": ["simulate", "--t-end", "50", "--no-progress"],
    "floquet": ["floquet"],
}
#: Fills numba's cache for the laws of every command here (compiled in the foreground).
_WARM_UP = (
    "from beltmdsm import floquet, simulate\n"
    "simulate(t_end=5.0, backend='numba')\n"
    "floquet(backend='numba')\n"
)


def _stop_compiles(cache):
    """Stop the child compiling into ``cache`` (its pid is in its claim files): the
    compile is not the measured process's, and would slow the next measurement. It
    claims each job after starting (a second or two), so 3 s without a claim end it."""
    ready = os.path.join(cache, "numba", "beltmdsm-ready")
    deadline = time.perf_counter() + 3.0
    while time.perf_counter() < deadline:
        names = os.listdir(ready) if os.path.isdir(ready) else []
        for name in (n for n in names if n.endswith(".compiling")):
            try:
                with open(os.path.join(ready, name)) as fh:
                    os.kill(int(fh.read()), signal.SIGKILL)
                deadline = time.perf_counter() + 1.0
            except (OSError, ValueError):
                pass
        time.sleep(0.05)


def cold(command, repeat):
    """Median wall time of ``command`` in processes with fresh, empty caches."""
    walls = []
    for _ in range(repeat):
        cache = tempfile.mkdtemp(prefix="bench-start-")
        env = dict(
            os.environ,
            NUMBA_CACHE_DIR=os.path.join(cache, "numba"),
            BELTMDSM_CACHE=os.path.join(cache, "beltmdsm"),
        )
        try:
            walls.append(_wall(command, env))
        finally:
            _stop_compiles(cache)
            shutil.rmtree(cache, ignore_errors=True)
    return statistics.median(walls)


def warm(command, repeat):
    """Median wall time of ``command`` with the caches filled (after a run not counted)."""
    _wall(command)
    return statistics.median(_wall(command) for _ in range(repeat))


def paired(a, b, repeat):
    """Medians of the wall times of ``a`` and ``b`` taken in turn, and of the ratios a/b."""
    _wall(a), _wall(b)  # not counted: disk caches, numba's cache
    walls_a, walls_b = [], []
    for _ in range(repeat):
        walls_a.append(_wall(a))
        walls_b.append(_wall(b))
    ratios = [x / y for x, y in zip(walls_a, walls_b)]
    return statistics.median(walls_a), statistics.median(walls_b), statistics.median(ratios)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="8 points of 300 s for the sweep")
    ap.add_argument("--repeat", type=int, default=5, help="counted runs of each (default 5)")
    args = ap.parse_args(argv)
    points, t_end = (8, 300.0) if args.quick else (32, 1000.0)
    for package in ("beltmdsm", "generated", "derive", "benchmarks"):
        compileall.compile_dir(ROOT / package, quiet=1)
    py = [sys.executable, "-c"]
    help_s, bare_s, help_ratio = paired(
        [sys.executable, "-m", "beltmdsm", "--help"], py + ["pass"], args.repeat
    )
    print(
        f"beltmdsm --help: {help_s:.3f} s, {help_ratio:.1f}x the interpreter's start "
        f"({bare_s:.3f} s) (target: under 0.5 s)"
    )
    ours, theirs, ratio = paired(
        py + ["import beltmdsm"], py + ["import numpy, scipy.integrate"], args.repeat
    )
    print(
        f"import beltmdsm: {ours:.3f} s, {ratio:.2f}x import numpy, scipy.integrate "
        f"({theirs:.3f} s) (target: at most 1.5x)"
    )
    cli = [sys.executable, "-m", "beltmdsm"]
    cold_s = {name: cold(cli + argv, args.repeat) for name, argv in FIRST_RUNS.items()}
    subprocess.run(py + [_WARM_UP], cwd=ROOT, check=True, capture_output=True)
    warm_s = {name: warm(cli + argv, args.repeat) for name, argv in FIRST_RUNS.items()}
    for (name, c), target in zip(cold_s.items(), (3, 5)):
        print(
            f"first run, whole process: {name} cold {c:.2f} s (fresh caches; target: "
            f"within {target} s), warm {warm_s[name]:.2f} s"
        )
    base_s, sweep_s, ratio = paired(
        _baseline_command(points, t_end), _sweep_command(points, t_end), max(1, args.repeat // 2)
    )
    cold_sweep_s = cold(_sweep_command(points, t_end), max(1, args.repeat // 2))
    print(
        f"{points}-point sweep of {t_end:g} s runs, whole processes: beltmdsm sweep "
        f"{sweep_s:.2f} s warm, {cold_sweep_s:.2f} s cold (fresh caches), baseline "
        f"(solve_ivp RK45, rtol 1e-9, np.sign) {base_s:.2f} s: the sweep is {ratio:.1f}x "
        f"faster warm (target: at least 25x), {base_s / cold_sweep_s:.1f}x cold"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
