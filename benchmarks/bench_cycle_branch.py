"""Speed of a branch of self-excited cycles (issue 29, item 7: 100 points under 30 s).

The branch of the Stribeck base set without excitation, ``Vb`` over 0.5-3 (born at the
Hopf point, through the stick onset to the range's end: about 100 points), timed in
process after one run not counted (numba compiles and caches the kernels), the
median of ``--repeat`` runs, against a baseline measured in the same run: the same
cycles by natural-parameter continuation with `beltmdsm.periodic.cycle.cycle` at each
point's value, each seeded from the one before (the straightforward way; it cannot
pass the nonsmooth fold at the stick onset, so it walks each part of the branch on its
own from the branch's first point of that part). Points per second for both, and the
ratio. Run from the repository root: ``python -m benchmarks.bench_cycle_branch``.
"""

from __future__ import annotations

import argparse
import statistics
import time

from beltmdsm.continuation.branch import branch
from beltmdsm.model import Model
from beltmdsm.periodic.cycle import cycle

MODEL = Model(friction="stribeck", alpha=0)


def _branch():
    clock = time.perf_counter()
    found = branch(MODEL, param="Vb", lo=0.5, hi=3.0)
    return time.perf_counter() - clock, found


def _natural(found):
    """``cycle`` at every point's value, each seeded from the previous one of its part."""
    clock, previous, failures = time.perf_counter(), None, 0
    for q in found.points:
        if previous is None or (previous.n_sticks > 0) != (q.n_sticks > 0):
            guess = (q.state, q.period)  # a new part starts from the branch's point
        else:
            guess = (previous.state, previous.period)
        try:
            previous = cycle(MODEL.replace(Vb=q.value), *guess)
        except Exception:  # noqa: BLE001 - counted, the baseline goes on
            failures += 1
            previous = None
    return time.perf_counter() - clock, failures


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3, help="counted runs (default 3)")
    args = ap.parse_args(argv)
    _branch()  # not counted: compiles and caches the kernels
    runs = [_branch() for _ in range(max(1, args.repeat))]
    wall = statistics.median(w for w, _ in runs)
    found = runs[0][1]
    n = len(found.points)
    base, failures = (
        statistics.median([_natural(found)[0] for _ in range(max(1, args.repeat))]),
        _natural(found)[1],
    )
    print(
        f"branch of cycles, Stribeck base set, Vb 0.5-3: {n} points in {wall:.2f} s "
        f"({n / wall:.1f} points/s; target: 100 points under 30 s), special points "
        + ", ".join(f"{s.kind} {s.value:.6g}" for s in found.special)
    )
    print(
        f"baseline, cycle() at the same {n} values seeded from the neighbour: {base:.2f} s "
        f"({n / base:.1f} points/s, {failures} not converged): the branch takes "
        f"{wall / base:.2f}x its time (and passes the fold, locates the special points)"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
