"""Basin stability of the friction oscillator (issue 40, item 4): ours against the peers'
ensemble, side by side on the same starts.

* **baseline** (pyBasin's JAX way): the 1-DOF friction oscillator of bSTAB/pyBasin
  (x'' = -x - 2 xi x' - mu(v_r) sgn v_r, mu = mu_d (1 + (mu_sd - 1) e^{-|v_r|/v0})),
  written here in jax.numpy as pyBasin's JAX right-hand side does: the sign smoothed
  by ``tanh(200 v_r)``, a stick band ``|v_r| < 1e-4`` inside which the velocity relaxes
  to the belt's; diffrax's Dopri5 ``vmap``ed over the starts, on the CPU, float32,
  ``rtol = 1e-8``, ``atol = 1e-6``, t in [0, 500]; a start is steady sliding where its
  velocity stays within 1e-2 of 0 over t in [450, 500] (saved at 50 points), else the
  stick-slip cycle. Needs the ``bench`` extra (``pip install -e '.[bench]'``: jax,
  diffrax), never a dependency of the package.
* **ours**: `beltmdsm.basin.basin_stability.basin_stability` on the same model
  (``--alpha 0 --omega1 1 --beta1 0.05 --g 1 --friction stribeck --mu_s 1.0 --mu_k 0.5
  --v_s 0.5``, Vb = 1.5): each start decided as soon as it provably lands, by the
  region the computed cycles assign it to, or by sticking, else by a run
  (`beltmdsm.attractors.self_excited`). Timed with the invariant sets computed
  (`beltmdsm.basin.basin_stability.landscape_of`: the branch of cycles, their orbits,
  the stick end's fate) and without (the starts alone, the sets given).

"Cold" is the first call in the process (the JIT compile of the baseline; our kernels
from numba's disk cache, the branch computed); "warm" a second call on the same starts.
Both estimates come with their standard errors and the starts on which they disagree.

Every estimate runs without the disk cache (a "warm" call that read the cold call's
files would time the files).

``--dask`` times our estimate on a ``distributed.LocalCluster`` of 1 and of 2
single-threaded workers, in the same run, at Vb = 1.5 (every start decided by region:
nothing is sent) and at Vb = 2.0 (most starts run until they stick): the sets computed
first, once; each worker warmed, its first run (numba's kernels loaded) printed
apart. It says where the time goes: the wall times and their ratio under the load of
the moment (``uptime`` before and after), the CPU seconds of each worker process and
of this process (the client and the LocalCluster's scheduler), and from those the
ratio on an idle machine (`_idle`).

Run from the repository root: ``python -m benchmarks.bench_basin_stability [--samples N]
[--seed S] [--dask] [--no-baseline]``. The figures depend on the machine and its load:
run it alone, and read ``uptime``.
"""

from __future__ import annotations

import argparse
import math
import os
import time

import numpy as np

from beltmdsm.basin.basin_stability import basin_stability, draw_starts, landscape_of
from beltmdsm.model import Model

CASE = dict(alpha=0.0, omega1=1.0, beta1=0.05, g=1.0, friction="stribeck", mu_s=1.0, mu_k=0.5,
            v_s=0.5, Vb=1.5)  # fmt: skip
BOX = {"X1": (-2.0, 2.0), "Y1": (0.0, 2.0)}


def _timed(fn):
    t0 = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t0


def baseline(starts, vb=1.5):
    """The peers' labels (0 steady sliding, 1 cycle) of ``starts`` (n, 2), a function
    that runs them again, and its first (compiling) time."""
    import diffrax
    import jax
    import jax.numpy as jnp

    xi, mud, musd, v0, k, eta = 0.05, 0.5, 2.0, 0.5, 200.0, 1e-4

    def field(t, y, args):
        x, v = y[0], y[1]
        vr = v - vb
        mu = mud + mud * (musd - 1.0) * jnp.exp(-jnp.abs(vr) / v0)
        slip = jnp.abs(vr) > eta
        breaks = jnp.abs(x + 2 * xi * v) > mud * musd
        a_slip = -x - 2 * xi * v - jnp.tanh(k * vr) * mu
        a_break = -x - 2 * xi * v + mud * musd * jnp.tanh(k * mu)
        a_stick = -(v - vb)
        dx = jnp.where(slip | breaks, v, vb)
        dv = jnp.where(slip, a_slip, jnp.where(breaks, a_break, a_stick))
        return jnp.stack([dx, dv])

    term = diffrax.ODETerm(field)
    solver = diffrax.Dopri5()
    control = diffrax.PIDController(rtol=1e-8, atol=1e-6)
    saveat = diffrax.SaveAt(ts=jnp.linspace(450.0, 500.0, 50, dtype=jnp.float32))

    def one(y0):
        sol = diffrax.diffeqsolve(
            term, solver, 0.0, 500.0, 0.01, y0, saveat=saveat, stepsize_controller=control,
            max_steps=1_000_000,
        )  # fmt: skip
        return jnp.max(jnp.abs(sol.ys[:, 1]))

    run = jax.jit(jax.vmap(one))
    y0 = jnp.asarray(starts, dtype=jnp.float32)

    def go():
        return np.asarray(jax.block_until_ready(run(y0)))

    amp, cold = _timed(go)
    return (amp > 1e-2).astype(int), go, cold


def _estimate(labels, label):
    p = float(np.mean(labels == label))
    return p, math.sqrt(p * (1 - p) / len(labels))


def _warm(ls):
    """Run on every worker before the timing: load the integrator's kernels (numba's
    disk cache) with one run, which a chunk decided by region alone never needs; the
    seconds (wall, CPU) it took there."""
    t0, c0 = time.perf_counter(), time.process_time()
    ls._run(ls.equilibrium.state + np.array([0.0, 1.9, 0.0, 0.0]), 20.0, None)
    return time.perf_counter() - t0, time.process_time() - c0


def _cpu():
    return time.process_time(), _BUSY[0]


#: This worker's CPU seconds in tasks (`_timed_call`).
_BUSY = [0.0]


def _timed_call(fn, *args):
    c0 = time.thread_time()
    try:
        return fn(*args)
    finally:
        _BUSY[0] += time.thread_time() - c0


class _Timed:
    """A dask executor whose tasks add their thread's CPU seconds to their worker's
    `_BUSY` (the worker's other CPU is its event loop: heartbeats, transfers)."""

    def __init__(self, client):
        self.inner, self._client = client.get_executor(), client

    def submit(self, fn, *args):
        # by the module's name: run as __main__, cloudpickle would ship a copy of the
        # function with its own _BUSY
        from benchmarks import bench_basin_stability as me

        return self.inner.submit(me._timed_call, fn, *args)


def _dask(model, ls, samples, seed, profiler=True):
    """Per number of single-threaded dask workers (1, 2): the wall seconds of the
    estimate (sets given, workers warmed, no cache), the CPU seconds each worker
    process spent meanwhile, this process's (the client and the LocalCluster's
    scheduler, which runs here), and each worker's first run (numba's
    kernels loaded: wall, CPU)."""
    import dask
    from distributed import Client, LocalCluster

    from benchmarks import bench_basin_stability as me  # see _Timed.submit

    out = {}
    for n in (1, 2):
        # the workers' statistical profiler samples the task thread every 10 ms (dask's
        # default); --no-worker-profiler measures without it
        with dask.config.set({"distributed.worker.profile.enabled": profiler}):
            cluster = LocalCluster(
                n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None
            )
        with cluster, Client(cluster) as client:
            ex = _Timed(client)
            first = list(client.run(_warm, ls).values())
            basin_stability(model, BOX, samples=200, seed=seed + 1, landscape=ls, executor=ex,
                            cache_dir=None)  # fmt: skip
            w0, p0 = client.run(me._cpu), time.process_time()
            t0 = time.perf_counter()
            basin_stability(model, BOX, samples=samples, seed=seed, landscape=ls, executor=ex,
                            cache_dir=None)  # fmt: skip
            wall = time.perf_counter() - t0
            w1, p1 = client.run(me._cpu), time.process_time()
        # (tasks, process) of each worker, the busiest first
        cpu = sorted(((w1[k][1] - w0[k][1], w1[k][0] - w0[k][0]) for k in w0), reverse=True)
        out[n] = dict(wall=wall, workers=[c for _, c in cpu], tasks=[b for b, _ in cpu],
                      parent=p1 - p0, first=first)  # fmt: skip
    return out


def _idle(t, overhead=True):
    """The wall time of the run on an idle machine, a core per worker: the busiest
    worker's task CPU (``overhead=False``: the split alone). With the overhead: the
    event loops of the workers and of this process spend CPU per second of wall time
    (heartbeats, the scheduler's and profiler's periodic work), measured here as rates
    (under load the wall time is longer, so their seconds are not what an idle run
    spends); the run then takes the longer of the busiest worker's tasks with its own
    loop's rate, and all the tasks spread over the cores left by every loop's rate."""
    if not overhead:
        return t["tasks"][0]
    cores = os.cpu_count() or 1
    loops = [(w - c) / t["wall"] for w, c in zip(t["workers"], t["tasks"])]
    rate = sum(loops) + t["parent"] / t["wall"]
    return max(t["tasks"][0] / (1.0 - loops[0]), sum(t["tasks"]) / (cores - rate))


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--samples", type=int, default=4000)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--dask", action="store_true")
    ap.add_argument("--no-baseline", action="store_true")
    ap.add_argument("--dask-only", action="store_true", help="only the dask scaling")
    ap.add_argument("--no-worker-profiler", action="store_true",
                    help="dask workers without their statistical profiler")  # fmt: skip
    ap.add_argument("--dask-vb", type=float, nargs="+", default=[1.5, 2.0],
                    help="the belt speeds of the dask scaling")  # fmt: skip
    args = ap.parse_args(argv)
    n = args.samples
    model = Model(**CASE)
    print(f"uptime: {os.popen('uptime').read().strip()}")
    if args.dask_only:
        args.dask, args.no_baseline = True, True

    # ours: cold (the sets computed), warm (again), the starts alone (sets given)
    (ls, t_sets_cold) = _timed(lambda: landscape_of(model))
    ours, t_cold = _timed(
        lambda: basin_stability(model, BOX, samples=n, seed=args.seed, landscape=ls, cache_dir=None)
    )
    ls2, t_sets = _timed(lambda: landscape_of(model))
    again, t_warm = _timed(
        lambda: basin_stability(
            model, BOX, samples=n, seed=args.seed, landscape=ls2, cache_dir=None
        )
    )
    assert np.array_equal(ours.labels, again.labels)
    print(f"N = {n} starts of the friction case at Vb = 1.5, box X1 in [-2, 2], X1' in [0, 2]")
    print(f"ours: invariant sets {t_sets_cold:.2f} s cold, {t_sets:.2f} s warm; starts "
          f"{t_cold:.3f} s cold, {t_warm:.3f} s warm")  # fmt: skip
    per_total = (t_sets + t_warm) / n * 1e3
    per_starts = t_warm / n * 1e3
    per_cold = (t_sets_cold + t_cold) / n * 1e3
    print(
        f"  per start, warm: {per_total:.4f} ms with the sets, {per_starts:.4f} ms the "
        f"starts alone; cold: {per_cold:.4f} ms"
    )
    d = ours.decided
    print(f"  decided by region at once: {d['region']}, by a run until it stuck: {d['stick']},"
          f" undecided: {d['none']}")  # fmt: skip
    p, e = ours.fraction(0)
    print(f"  steady sliding: {p:.4f} +- {e:.4f}; stick-slip cycle: {1 - p:.4f} +- {e:.4f}")

    if not args.no_baseline:
        starts = draw_starts(ls.equilibrium.state, BOX, n, args.seed)[:, :2]
        peer, go, t_bcold = baseline(starts)
        _, t_bwarm = _timed(go)
        bp, be = _estimate(peer, 0)
        print(f"baseline (JAX, diffrax Dopri5, vmap, float32, CPU): {t_bcold:.2f} s with compile,"
              f" {t_bwarm:.2f} s warm")  # fmt: skip
        print(
            f"  per start: {t_bcold / n * 1e3:.4f} ms with compile, {t_bwarm / n * 1e3:.4f} ms warm"
        )
        print(f"  steady sliding: {bp:.4f} +- {be:.4f}; stick-slip cycle: {1 - bp:.4f} +- {be:.4f}")
        mine = (ours.labels != 0).astype(int)
        print(f"  starts classified alike: {int(np.sum(mine == peer))} of {n}")
        print(f"ratio (baseline / ours), per start warm: {t_bwarm / (t_sets + t_warm):.1f}x with "
              f"our sets computed, {t_bwarm / t_warm:.1f}x the starts alone")  # fmt: skip
    if args.dask:
        # at Vb = 1.5 the starts are decided by region (no run: nothing worth sending);
        # at Vb = 2.0 no cycle bounds the basin and most starts are run until they stick,
        # which is work the workers split
        for vb in args.dask_vb:
            at = model.replace(Vb=vb)
            sets = ls if vb == 1.5 else landscape_of(at)
            run = int(
                np.sum(sets.decide(draw_starts(sets.equilibrium.state, BOX, n, args.seed)) < 0)
            )
            print(f"dask LocalCluster at Vb = {vb}, N = {n} ({run} starts run, {n - run} decided "
                  f"by region at once), sets given, no cache, workers' profiler "
                  f"{'off' if args.no_worker_profiler else 'on'}:")  # fmt: skip
            print(f"  uptime: {os.popen('uptime').read().strip()}")
            t = _dask(at, sets, n, args.seed, profiler=not args.no_worker_profiler)
            for k in (1, 2):
                r = t[k]
                first = ", ".join(f"{w:.2f}/{c:.2f}" for w, c in r["first"])
                print(f"  {k} worker{'s' if k > 1 else ''}: wall {r['wall']:.3f} s; CPU s: in "
                      f"tasks {', '.join(f'{c:.3f}' for c in r['tasks'])}, worker processes "
                      f"{', '.join(f'{c:.3f}' for c in r['workers'])}, this process (client "
                      f"+ scheduler) {r['parent']:.3f}; first run per worker (kernels loaded, "
                      f"before the timing) {first} s wall/CPU")  # fmt: skip
            print(f"  2 workers against 1: {t[1]['wall'] / t[2]['wall']:.2f}x wall (under this "
                  f"load); idle estimates from the CPU seconds: "
                  f"{_idle(t[1], False) / _idle(t[2], False):.2f}x the split of the tasks "
                  f"alone, {_idle(t[1]) / _idle(t[2]):.2f}x with the event loops' CPU per "
                  f"second measured here")  # fmt: skip
            print(f"  uptime: {os.popen('uptime').read().strip()}")


if __name__ == "__main__":
    main()
