"""Speed of ``responses`` and ``coexistence`` (issue 20, item 6), whole processes, one core.

Every figure is a whole process timed from outside (the median of ``--repeat`` runs
after one not counted; the command and its baseline taken in turn, as in
benchmarks/bench_start.py), each against a baseline measured in the same run:

1. ``python -m beltmdsm responses --Vb 5`` (every periodic response at one point: the
   T-periodic one and the locked ones, from the run from rest, the run from the
   periodic start and two ladders) against one run of Eq. (4) from rest,
   ``python -m beltmdsm simulate --Vb 5`` (1000 s), which shows one attractor only
   (target: the responses under 5 s);
2. ``python -m beltmdsm coexistence --param Vb --from 0.5 --to 12`` (the base set's
   coexistence map, exact) against the brute-force map it replaces on the same 0.5 m/s
   grid: sweeps of 1000 s runs from rest and continued up and down
   (``sweep --continue``), without the cache (target: the coexistence under 60 s).

numba compiles the kernels once and caches them on disk: the first run of each, not
counted, fills that cache. Run from the repository root:
``python -m benchmarks.bench_locked [--repeat N]``.
"""

from __future__ import annotations

import argparse
import sys

from benchmarks.bench_start import _wall, paired

PY = [sys.executable, "-m", "beltmdsm"]
GRID = ["--param", "Vb", "--from", "0.5", "--to", "12"]
SWEEP = [*GRID, "--step", "0.5", "--jobs", "1", "--no-cache", "--no-progress"]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3, help="counted runs of each (default 3)")
    args = ap.parse_args(argv)
    ours, run, ratio = paired(
        PY + ["responses", "--Vb", "5"], PY + ["simulate", "--Vb", "5"], args.repeat
    )
    print(
        f"responses --Vb 5: {ours:.2f} s (target: under 5 s), {ratio:.1f}x one run from rest "
        f"(simulate --Vb 5, 1000 s: {run:.2f} s)"
    )
    _wall(PY + ["coexistence", *GRID])  # not counted
    exact = [_wall(PY + ["coexistence", *GRID]) for _ in range(max(1, args.repeat // 2))]
    brute = sum(
        _wall(PY + ["sweep", *SWEEP, *extra])
        for extra in ([], ["--continue", "up"], ["--continue", "down"])
    )
    best = min(exact)
    print(
        f"coexistence over Vb 0.5-12: {best:.1f} s (best of {len(exact)}; target: under "
        f"60 s); the brute-force map on the same grid (sweeps from rest, up and down, "
        f"24 points each): {brute:.1f} s, {brute / best:.1f}x the exact one"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
