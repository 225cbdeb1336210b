"""Speed of the basin map (issue 31, item 5): starts per second per core against the naive
loop, and the speed-up of 2 dask workers over 1.

* **ours**: `beltmdsm.studies.basins.basins` on a ``points x points`` grid of (X1, X1')
  at the base set, Vb = 3.88, where the T-periodic response and the 4T lock coexist:
  each start iterated on the closed-form period map and stopped once an attractor
  claims it. Timed whole (the attractors' classification included) and its landing
  rounds alone.
* **naive baseline**: one `beltmdsm.simulate` per start (the default 1000 s run with its
  summary), the attractor told by the omega1 peak of the spectrum (present: the 4T
  lock, the self-excited component at Omega / 4; absent: the T-periodic response), on a
  subsample of the starts. Its labels are compared with ours.
* **dask**: the same map on a ``distributed.LocalCluster`` of 1 and of 2 single-threaded
  worker processes (warmed by a small map first, so that no compile is timed).

Run from the repository root: ``python -m benchmarks.bench_basins [--points N]
[--naive N] [--no-dask]``. The figures depend on the machine and its load: run it alone.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from beltmdsm import Model, simulate
from beltmdsm.studies import basins as basins_module
from beltmdsm.studies.basins import basins

MODEL = Model(Vb=3.88)
PLANE = dict(x_range=(1.0, 9.0), y_range=(-10.5, -2.5), t_end=1000.0)


def _timed(fn):
    t0 = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t0


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=12)
    ap.add_argument("--naive", type=int, default=12, help="starts of the naive baseline")
    ap.add_argument("--no-dask", action="store_true")
    args = ap.parse_args(argv)

    basins(MODEL, points=2, **PLANE)  # compile the kernels outside the timed region
    landing = []
    real_map_all = basins_module._map_all

    def timed_map_all(fn, items, executor):
        out, dt = _timed(lambda: real_map_all(fn, items, executor))
        landing.append(dt)
        return out

    basins_module._map_all = timed_map_all
    try:
        ours, total = _timed(lambda: basins(MODEL, points=args.points, **PLANE))
    finally:
        basins_module._map_all = real_map_all
    n = ours.labels.size
    land = sum(landing)
    print(f"basins: {n} starts, {ours!r}")
    print(f"  ours, whole map:        {total:8.2f} s   {n / total:8.2f} starts/s")
    print(f"  ours, landing only:     {land:8.2f} s   {n / land:8.2f} starts/s")

    # the naive loop on a subsample of the grid (every k-th start)
    flat = np.argwhere(np.ones_like(ours.labels, dtype=bool))
    pick = flat[np.linspace(0, n - 1, min(args.naive, n)).astype(int)]
    base = ours.attractors[0].points[0]
    four = [a.label for a in ours.attractors if a.attractor.periods == 4]
    agree, t_naive = 0, 0.0
    for i, j in pick:
        y0 = base.copy()
        y0[:2] = ours.xs[j], ours.ys[i]
        sim, dt = _timed(lambda y0=y0: simulate(MODEL, y0=y0, progress=False))
        t_naive += dt
        naive_is_4T = bool(sim.summary.omega1_peak_present)
        agree += naive_is_4T == (int(ours.labels[i, j]) in four)
    per_naive = t_naive / len(pick)
    print(
        f"  naive simulate loop:    {per_naive:8.3f} s a start ({len(pick)} starts), "
        f"{1 / per_naive:8.2f} starts/s; labels agree with ours at {agree}/{len(pick)}"
    )
    print(
        f"  ratio (naive s/start over ours): whole map {per_naive / (total / n):6.1f}x, "
        f"landing {per_naive / (land / n):6.1f}x"
    )

    if args.no_dask:
        return
    from distributed import Client, LocalCluster

    times = {}
    for workers in (1, 2):
        with (
            LocalCluster(
                n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None
            ) as cluster,
            Client(cluster) as client,
        ):
            ex = client.get_executor()
            basins(MODEL, points=2, executor=ex, **PLANE)  # warm the workers
            landing.clear()
            basins_module._map_all = timed_map_all
            try:
                basins(MODEL, points=args.points, executor=ex, **PLANE)
            finally:
                basins_module._map_all = real_map_all
            times[workers] = sum(landing)
            print(f"  dask, {workers} worker(s), landing: {times[workers]:8.2f} s")
    print(f"  speed-up of 2 workers over 1: {times[1] / times[2]:.2f}x")


if __name__ == "__main__":
    main()
