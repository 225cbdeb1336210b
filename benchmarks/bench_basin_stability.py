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

``--dask`` times our estimate on a ``distributed.LocalCluster`` of 1 and of 2
single-threaded workers (the sets computed first, once; each worker warmed) and says
where the time goes.

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
    disk cache) with one run, which a chunk decided by region alone never needs."""
    ls._run(ls.equilibrium.state + np.array([0.0, 1.9, 0.0, 0.0]), 20.0, None)


def _dask(model, ls, samples, seed):
    """Seconds of the estimate on 1 and on 2 single-threaded dask workers (warmed)."""
    from distributed import Client, LocalCluster

    out = {}
    for n in (1, 2):
        cluster = LocalCluster(
            n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None
        )
        with cluster, Client(cluster) as client:
            ex = client.get_executor()
            client.run(_warm, ls)
            basin_stability(model, BOX, samples=200, seed=seed + 1, landscape=ls, executor=ex)
            t0 = time.perf_counter()
            basin_stability(model, BOX, samples=samples, seed=seed, landscape=ls, executor=ex)
            out[n] = time.perf_counter() - t0
    return out


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--samples", type=int, default=4000)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--dask", action="store_true")
    ap.add_argument("--no-baseline", action="store_true")
    ap.add_argument("--dask-only", action="store_true", help="only the dask scaling")
    args = ap.parse_args(argv)
    n = args.samples
    model = Model(**CASE)
    print(f"uptime: {os.popen('uptime').read().strip()}")
    if args.dask_only:
        args.dask, args.no_baseline = True, True

    # ours: cold (the sets computed), warm (again), the starts alone (sets given)
    (ls, t_sets_cold) = _timed(lambda: landscape_of(model))
    ours, t_cold = _timed(
        lambda: basin_stability(model, BOX, samples=n, seed=args.seed, landscape=ls)
    )
    ls2, t_sets = _timed(lambda: landscape_of(model))
    again, t_warm = _timed(
        lambda: basin_stability(model, BOX, samples=n, seed=args.seed, landscape=ls2)
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
        # at Vb = 1.5 the starts are decided by region (no run: little to split); at
        # Vb = 2.0 no cycle bounds the basin and a third of the starts are run until they
        # stick, which is work a worker does
        for vb in (1.5, 2.0):
            at = model.replace(Vb=vb)
            sets = ls if vb == 1.5 else landscape_of(at)
            t = _dask(at, sets, n, args.seed)
            d = basin_stability(at, BOX, samples=n, seed=args.seed, landscape=sets).decided
            print(
                f"dask LocalCluster at Vb = {vb} ({d['stick']} of {n} starts run), sets "
                f"given: 1 worker {t[1]:.3f} s, 2 workers {t[2]:.3f} s: {t[1] / t[2]:.2f}x"
            )


if __name__ == "__main__":
    main()
