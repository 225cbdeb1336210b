"""Speed of the basin map (issue 31, item 5): starts per second per core against the naive
loop, and the speed-up of 2 dask workers over 1.

* **ours**: `beltmdsm.basin.basins.basins` on a ``points x points`` grid of (X1, X1')
  at the base set, Vb = 3.88, where the T-periodic response and the 4T lock coexist:
  each start iterated on the closed-form period map and stopped once an attractor
  claims it (within a claim radius measured from a pilot of the starts, and closer
  one cycle later: `beltmdsm.attractors.recurrence`). Timed whole (the attractors'
  seeding included) and its landing alone (the pilot's and the rest's).
* **naive baseline**: one `beltmdsm.simulate` per start (the default 1000 s run with its
  summary), the attractor told by the omega1 peak of the spectrum (present: the 4T
  lock, the self-excited component at Omega / 4; absent: the T-periodic response), on a
  subsample of the starts. Its labels are compared with ours.
* **dask**: the same map (``--dask-points``, default 24 x 24: a 12 x 12 map is under a
  second of work, too little to time a split) on a ``distributed.LocalCluster`` of 1 and
  of 2 single-threaded worker processes (warmed by a small map first, so that no
  compile is timed), each timed ``--repeat`` times (the best kept). Besides the wall
  time, the CPU seconds each worker spent (psutil): where the machine's cores are
  shared with other work, a worker gets a fraction of a core and the wall-time
  speed-up says more about the load than about the split; the CPU seconds show
  whether the split itself adds work or leaves a worker idle (the speed-up on free
  cores: 1-worker CPU over the busiest of the 2 workers' CPU).

Run from the repository root: ``python -m benchmarks.bench_basins [--points N]
[--naive N] [--no-dask] [--dask-points N] [--repeat N]``. The figures depend on the
machine and its load: run it alone.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from beltmdsm import Model, simulate
from beltmdsm.basin import basins as basins_module
from beltmdsm.basin.basins import basins

MODEL = Model(Vb=3.88)
PLANE = dict(x_lo=1.0, x_hi=9.0, y_lo=-10.5, y_hi=-2.5, t_end=1000.0)


def _timed(fn):
    t0 = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t0


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=12)
    ap.add_argument("--naive", type=int, default=12, help="starts of the naive baseline")
    ap.add_argument("--no-dask", action="store_true")
    ap.add_argument("--dask-points", type=int, default=24)
    ap.add_argument("--repeat", type=int, default=2)
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
    import os

    import psutil
    from distributed import Client, LocalCluster

    best = {}
    for workers in (1, 2):
        with (
            LocalCluster(
                n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None
            ) as cluster,
            Client(cluster) as client,
        ):
            ex = client.get_executor()
            basins(MODEL, points=3, executor=ex, **PLANE)  # warm the workers
            procs = [psutil.Process(pid) for pid in client.run(os.getpid).values()]
            for _ in range(args.repeat):
                cpu0 = [sum(p.cpu_times()[:2]) for p in procs]
                landing.clear()
                basins_module._map_all = timed_map_all
                try:
                    basins(MODEL, points=args.dask_points, executor=ex, **PLANE)
                finally:
                    basins_module._map_all = real_map_all
                cpu = [sum(p.cpu_times()[:2]) - c for p, c in zip(procs, cpu0)]
                wall = sum(landing)
                share = sum(cpu) / (wall * workers)
                print(
                    f"  dask, {workers} worker(s), {args.dask_points**2} starts: landing "
                    f"{wall:6.2f} s, worker CPU {', '.join(f'{c:.2f}' for c in cpu)} s "
                    f"({100 * share:.0f}% of a core each), load {os.getloadavg()[0]:.1f}"
                )
                if workers not in best or wall < best[workers][0]:
                    best[workers] = (wall, cpu)
    (w1, c1), (w2, c2) = best[1], best[2]
    print(f"  speed-up of 2 workers over 1: {w1 / w2:.2f}x wall")
    print(
        f"  on free cores (1 worker's CPU over the busiest of 2): {c1[0] / max(c2):.2f}x; "
        f"work added by the split: {100 * (sum(c2) / c1[0] - 1):+.0f}%"
    )


if __name__ == "__main__":
    main()
