"""A self-excited cycle by shooting against finding it by simulation alone (issue 29, item 7).

Stribeck friction without excitation (``alpha = 0``, mu_k = 0.25, v_s = 1 m/s, the
base set otherwise) at belt speeds where steady sliding is unstable. Times, on one
core (the code is single-threaded):

* **shooting**, `beltmdsm.periodic.cycle.cycle`: cold (the first call in a fresh
  process, kernels loaded from numba's cache), warm from scratch (the seed's run off
  steady sliding, then Newton's method with the monodromy; the median of
  ``--repeat`` calls) and warm from a neighbour's cycle (as a branch calls it); the
  cycle and its multipliers in each;
* **simulation alone**: a run of the event-driven integrator from the same perturbed
  equilibrium at the shooting's tolerance (1e-12), its returns to the same Poincare
  section (the minimum of X1') located by bisection on the field, run on until two
  successive periods agree to ``--tol`` (relative); its multipliers by central finite
  differences of that return map (8 runs of one period).

and prints the period each finds, how far apart they are, ``|mu_1 - 1|`` of the
shooting (its own accuracy) and the ratio of the times. These stick-slip cycles are
superstable (the stick's multiplier 0): a run is on the cycle to rounding one period
after its first stick, so simulation alone is as fast as the seeded shooting there,
both spent mostly growing away from steady sliding; shooting from a neighbour skips
that. Last, the unstable pure-slip cycle next to the (subcritical) Hopf point, which
shooting finds from the first-order averaged amplitude and simulation alone cannot
(a run started on it leaves it). Run from the repository root:
``python -m benchmarks.bench_cycles [--repeat N] [--tol T]``.
"""

from __future__ import annotations

import argparse
import math
import statistics
import subprocess
import sys
import time

import numpy as np

from beltmdsm.excitation import initial_state
from beltmdsm.integrate.events import integrate_events
from beltmdsm.integrate.switching import Switching
from beltmdsm.model import Model
from beltmdsm.periodic.cycle import cycle
from beltmdsm.settings import SolverSettings
from beltmdsm.starts.cycle_seed import SEED_AMPLITUDE, unstable_pair

SPEEDS = (0.5, 1.0, 1.5, 1.9)
LAW = dict(friction="stribeck", alpha=0.0)


def _model(vb):
    return Model(Vb=vb, **LAW)


def _returns(sw, tr, t0):
    """Times and states where X1' has an interior minimum in slip-back after ``t0``."""
    out = []
    for seg in tr.segments:
        if seg.mode != -1 or seg.t1 <= t0:
            continue
        t = np.linspace(seg.t0, seg.t1, max(int((seg.t1 - seg.t0) * 50), 8))
        v = tr.state(t)[1]
        for k in np.flatnonzero((v[1:-1] < v[:-2]) & (v[1:-1] <= v[2:])) + 1:
            a, b = t[k - 1], t[k + 1]

            def acc(s):
                return sw.field(s, *tr.state(np.array([s]))[:, 0], -1.0)[1]

            fa = acc(a)
            while b - a > 1e-13 * b:
                m = 0.5 * (a + b)
                if (acc(m) > 0) == (fa > 0):
                    a = m
                else:
                    b = m
            out.append((0.5 * (a + b), tr.state(np.array([0.5 * (a + b)]))[:, 0]))
    return out


def by_simulation(vb, tol):
    """``(period, state, multipliers, run_time)`` by a run and a Poincare section alone."""
    model = _model(vb)
    sw = Switching(model)
    lam, vec = unstable_pair(model)
    v = np.real(vec)
    y = initial_state(model) + SEED_AMPLITUDE * vb * v / abs(v[1])
    turn = 2 * math.pi / abs(lam.imag)
    t, found, last_T = 0.0, [], None
    clock = time.perf_counter()
    while True:
        settings = SolverSettings(
            t_end=t + 20 * turn, rtol=1e-12, atol=1e-12, dt=turn / 4, t_discard=t
        )
        tr = integrate_events(model, settings, y0=y, t0=t).trajectory
        found += _returns(sw, tr, t)
        t, y = tr.t_end, tr.state(np.array([tr.t_end]))[:, 0]
        if len(found) >= 2:
            T = found[-1][0] - found[-2][0]
            if last_T is not None and abs(T - last_T) <= tol * T:
                break
            last_T = T
    state = found[-1][1]

    def ret(x):
        settings = SolverSettings(t_end=1.3 * T, rtol=1e-12, atol=1e-12, dt=T / 50, t_discard=0)
        tr = integrate_events(model, settings, y0=x).trajectory
        near = [s for s in _returns(sw, tr, 0.5 * T)]
        return min(near, key=lambda r: abs(r[0] - T))[1]

    D = np.zeros((4, 4))
    for j in range(4):
        e = np.zeros(4)
        e[j] = 1e-6 * max(1.0, abs(state[j]))
        D[:, j] = (ret(state + e) - ret(state - e)) / (2 * e[j])
    mu = np.linalg.eigvals(D)
    return T, state, mu[np.argsort(-np.abs(mu))][:3], time.perf_counter() - clock


def _cold(vb):
    """The first call of ``cycle`` in a fresh process [s] (imports apart)."""
    code = (
        "import time; from beltmdsm.periodic.cycle import cycle; "
        "from beltmdsm.model import Model; c = time.perf_counter(); "
        f"cycle(Model(Vb={vb}, friction='stribeck', alpha=0.0)); "
        "print(time.perf_counter() - c)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return float(out.stdout.strip())


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="warm calls (median; default 5)")
    parser.add_argument(
        "--tol", type=float, default=1e-9, help="the simulation's period tolerance (1e-9)"
    )
    args = parser.parse_args(argv)
    cold = _cold(SPEEDS[0])
    cycle(_model(SPEEDS[0]))  # compile and cache every kernel in this process
    print(f"cold: the first cycle() in a fresh process {cold:.2f} s (Vb = {SPEEDS[0]})")
    ratios = []
    for vb in SPEEDS:
        times = []
        for _ in range(args.repeat):
            clock = time.perf_counter()
            c = cycle(_model(vb))
            times.append(time.perf_counter() - clock)
        warm = statistics.median(times)
        clock = time.perf_counter()
        cycle(_model(vb + 0.01), c.state, c.period)
        neighbour = time.perf_counter() - clock
        T, _, mu, sim = by_simulation(vb, args.tol)
        ratios.append(sim / warm)
        print(
            f"Vb = {vb:4}: shooting {warm:.3f} s from scratch, {neighbour:.3f} s from a "
            f"neighbour; period {c.period:.12f} s, |mu_1 - 1| = "
            f"{abs(c.trivial_multiplier - 1):.1e}, max|mu| = {c.max_abs_multiplier:.6f} | "
            f"simulation alone {sim:.3f} s: period {T:.12f} s (off by "
            f"{abs(T - c.period) / c.period:.1e}), max|mu| by finite differences "
            f"{np.max(np.abs(mu)):.6f} | ratio {sim / warm:.1f}x"
        )
    print(
        f"simulation alone / shooting (warm, from scratch): {min(ratios):.1f}x to "
        f"{max(ratios):.1f}x"
    )
    unstable_cycle()


def unstable_cycle(dv=0.05):
    """The pure-slip cycle at Vb = Vc + dv: shooting, and a run started on it."""
    from beltmdsm.generated import unforced

    probe = _model(1.0)
    vc = float(unforced.critical_belt_speed(**probe.arguments(unforced.critical_belt_speed)))
    model = _model(vc + dv)
    lam, vec = unstable_pair(model)
    x = initial_state(model) + math.sqrt(8 * (math.exp(dv) - 1)) * np.real(-vec / vec[1])
    clock = time.perf_counter()
    c = cycle(model, x, 2 * math.pi / abs(lam.imag))
    shoot = time.perf_counter() - clock
    periods = 400
    settings = SolverSettings(
        t_end=periods * c.period, rtol=1e-12, atol=1e-12, dt=c.period / 8, t_discard=0.0
    )
    tr = integrate_events(model, settings, y0=c.state + 1e-9).trajectory
    away = float(np.max(np.abs(tr.state(np.array([periods * c.period]))[:, 0] - c.state)))
    print(
        f"Vb = {vc + dv:.4f} (unstable pure slip): shooting {shoot:.3f} s, period "
        f"{c.period:.12f} s, |mu_1 - 1| = {abs(c.trivial_multiplier - 1):.1e}, max|mu| = "
        f"{c.max_abs_multiplier:.6f} | simulation alone: a run started 1e-9 off it is "
        f"{away:.2g} away after {periods} periods"
    )


if __name__ == "__main__":
    main()
