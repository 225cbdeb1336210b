"""Speed of the exact two-parameter map against a grid of ``floquet()`` calls (issue 20, item 5).

Times, in one run on one core, after compiling the kernels:

* ``beltmdsm.continuation.floquet_map.floquet_map`` over (Vb, beta1) = [0.5, 12] x [0.02, 0.6] with
  100 rows (the boundary curves traced by continuation, edges to about 1e-5 m/s), the
  median of ``--repeat`` runs (a run of half a second varies by 10 % from one to the
  next on a shared machine; the grid's ten seconds average over its calls);
* the baseline: ``beltmdsm.periodic.floquet.floquet()`` at every point of a grid with the same
  100 rows and ``--columns`` columns (default 100), each from scratch as a user's loop
  would call it; a point where it finds no periodic response counts as unstable;

and prints both times and their ratio (the issue's target: at least 20x). A grid with
100 columns locates an edge only to a column, 0.12 m/s; one that locates it to the
band's tolerance (1e-3 m/s, ``--matched``) needs 11501 columns: the benchmark then
times ``--matched-rows`` of its rows and scales the time to 100 rows.

It also checks the map against the grid: every grid point whose verdict differs from
the map's lies within one column of a map edge. Run from the repository root:
``python -m benchmarks.bench_floquet_map [--columns N] [--quick] [--matched]``.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from beltmdsm.continuation.floquet_map import floquet_map
from beltmdsm.errors import NoPeriodicResponse
from beltmdsm.model import Model
from beltmdsm.periodic.floquet import floquet

X, X_RANGE = "Vb", (0.5, 12.0)
Y, Y_RANGE = "beta1", (0.02, 0.6)
ROWS = 100
#: The band's tolerance: the grid that locates an edge to it has this spacing.
MATCHED_SPACING = 1e-3


def grid_row(y, xs):
    """``floquet()`` at each ``x`` of one row: True where unstable or none found."""
    out = np.empty(xs.size, dtype=bool)
    for i, x in enumerate(xs):
        try:
            out[i] = floquet({X: float(x), Y: float(y)}).stable is not True
        except NoPeriodicResponse:
            out[i] = True
    return out


def disagreements(unstable_rows, ys, xs, verdicts):
    """Grid points whose verdict differs from the map's farther than a column from an edge."""
    step = xs[1] - xs[0]
    bad = []
    for row, (y, unstable) in enumerate(zip(ys, unstable_rows)):
        inside = np.zeros(xs.size, dtype=bool)
        edges = []
        for lo, hi in unstable:
            inside |= (xs >= lo) & (xs <= hi)
            edges += [lo, hi]
        for i in np.flatnonzero(inside != verdicts[row]):
            if not edges or min(abs(xs[i] - e) for e in edges) > step:
                bad.append((float(y), float(xs[i])))
    return bad


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--columns", type=int, default=100, help="columns of the grid (100)")
    ap.add_argument(
        "--quick", action="store_true", help="time 10 of the grid's rows and scale to 100"
    )
    ap.add_argument(
        "--matched",
        action="store_true",
        help="also time a grid at the band's tolerance (1e-3 m/s), a few rows scaled",
    )
    ap.add_argument("--matched-rows", type=int, default=2)
    ap.add_argument("--repeat", type=int, default=5, help="runs of the map, median (5)")
    args = ap.parse_args(argv)

    # compile and warm every kernel outside the timed regions
    floquet(Model(Vb=5.0))
    floquet_map(None, X, *X_RANGE, Y, *Y_RANGE, points=3)

    runs = []
    for _ in range(max(args.repeat, 1)):
        clock = time.perf_counter()
        result = floquet_map(None, X, *X_RANGE, Y, *Y_RANGE, points=ROWS)
        runs.append(time.perf_counter() - clock)
    t_map = float(np.median(runs))

    ys = np.linspace(*Y_RANGE, ROWS)
    xs = np.linspace(*X_RANGE, args.columns)
    every = 10 if args.quick else 1
    rows = ys[::every]
    clock = time.perf_counter()
    verdicts = [grid_row(y, xs) for y in rows]
    t_grid = (time.perf_counter() - clock) * ROWS / rows.size
    bad = disagreements(result.unstable[::every], rows, xs, verdicts)

    print(
        f"map: {ROWS} rows of {Y} in [{Y_RANGE[0]:g}, {Y_RANGE[1]:g}], {X} in "
        f"[{X_RANGE[0]:g}, {X_RANGE[1]:g}]: {t_map:.2f} s (median of {len(runs)} runs, "
        f"{min(runs):.2f}-{max(runs):.2f}); curves: "
        + ", ".join(f"{c.kind} ({len(c.y)} rows)" for c in result.curves)
        + f"; bands on {len(result.band_rows)} rows"
    )
    worst = max(max(c.accuracy) for c in result.curves)
    print(f"  its edges to {worst:.1e} m/s")
    scaled = " (10 rows timed, scaled)" if args.quick else ""
    print(
        f"grid: {ROWS} x {args.columns} floquet() calls{scaled}: {t_grid:.2f} s; "
        f"ratio {t_grid / t_map:.1f}x (target >= 20x)"
    )
    print(
        f"  grid points whose verdict differs from the map's more than a column from an "
        f"edge: {len(bad)}"
    )
    if args.matched:
        columns = int(round((X_RANGE[1] - X_RANGE[0]) / MATCHED_SPACING)) + 1
        fine = np.linspace(*X_RANGE, columns)
        clock = time.perf_counter()
        for y in ys[:: max(ROWS // args.matched_rows, 1)][: args.matched_rows]:
            grid_row(y, fine)
        t_fine = (time.perf_counter() - clock) * ROWS / args.matched_rows
        print(
            f"grid at the band's tolerance: {ROWS} x {columns} floquet() calls "
            f"({args.matched_rows} rows timed, scaled): {t_fine:.0f} s; ratio "
            f"{t_fine / t_map:.0f}x"
        )


if __name__ == "__main__":
    main()
