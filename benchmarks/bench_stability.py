"""Speed against error of the stability functions (issue: forced system, item 6).

On N random parameter points (default 10^6, around the paper's base set, Vb up to
1.4 Vhat) it times, in one run:

* ``stability.is_stable``     (the Routh-Hurwitz verdict ``p > 0 and r > 0``, a sign per point)
* ``stability.growth_rate``   (closed-form roots of the two quadratics)

each with ``backend="numba"`` (when numba is installed; compiled before the timed
region) and ``backend="numpy"``, against

* ``numpy.linalg.eigvals``    of the same Jacobians ``stability.jacobian`` (the baseline;
  the Jacobians are built outside the timed region)
* the expanded ``H3 = a1 a2 a3 - a3^2 - a4 a1^2`` of Eq. (28) from ``stability.coefficients``

and prints each time, its ratio to the baseline, and its error against mpmath at 50
digits on a subsample (``mpmath.eig`` of the Jacobian for growth rates, the Hurwitz
signs for verdicts), plus the verdict errors on points 1e-12 (relative) from the
stability boundary, and 1e-14 from it for stiff tangential modes. `measure` returns
the rows (the notebook ``speed_vs_error`` plots them). Run from the repository root:
``python -m benchmarks.bench_stability [--n N] [--quick]``.
"""

from __future__ import annotations

import argparse
import importlib.util
import time
from dataclasses import dataclass

import mpmath
import numpy as np

from beltmdsm.generated import friction, stability
from beltmdsm.generated.mp import stability as mp_stability
from beltmdsm.generated.parameters import BASE

MODEL = ("beta1", "omega1", "beta2", "omega2", "alpha", "Omega", "mu_s", "g")


def sample(n, rng):
    """Every parameter random (log-uniform within a factor 3 of the base set): the worst
    case for array code, since no part of the computation is shared between points."""
    p = {k: BASE[k] * np.exp(rng.uniform(-np.log(3), np.log(3), n)) for k in MODEL}
    p["Vhat"] = friction.vhat(**p)
    p["Vb"] = p["Vhat"] * rng.uniform(0.0, 1.4, n)
    return p


def sample_map(n, rng):
    """A (beta1, Vb) stability map as in Fig. 6a: two meshgrid arrays (and the Vhat that
    follows from beta1), every other parameter at the base set. ``rng`` is unused."""
    side = int(round(np.sqrt(n)))
    beta1, Vb = np.meshgrid(np.linspace(0.01, 0.6, side), np.linspace(0.0, 12.0, side))
    p = {k: BASE[k] for k in MODEL}
    p["beta1"], p["Vb"] = beta1.ravel(), Vb.ravel()
    p["Vhat"] = friction.vhat(**p)
    return p


SCENARIOS = {"random": sample, "map": sample_map}


def stiff_sample(n, rng):
    """A stiff, lightly damped tangential mode next to a heavily damped normal one:
    where the expanded H3 cancels most (see tests/generated/test_stability.py)."""
    p = sample(n, rng)
    p["omega1"] = 10 ** rng.uniform(1.5, 2.5, n)
    p["beta1"] = 0.1 / p["omega1"]
    p["beta2"] = rng.uniform(2, 10, n)
    p["omega2"] = rng.uniform(0.5, 2, n)
    p["Vhat"] = rng.uniform(15, 30, n)
    return p


def near_boundary(n, rng, distance=1e-12, draw=sample):
    """Points at relative distance +-distance from the critical belt speed."""
    p = draw(4 * n, rng)
    crit = stability.critical_belt_speed(**p)
    keep = (crit > 0) & (crit < p["Vhat"])
    p = {k: v[keep][:n] for k, v in p.items()}
    side = np.where(np.arange(len(p["Vb"])) % 2 == 0, -1.0, 1.0)
    p["Vb"] = stability.critical_belt_speed(**p) * (1 + side * distance)
    return p


def best_of(fn, repeat):
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - start)
    return min(times), out


def point(p, i):
    return {k: float(v[i]) if np.ndim(v) else float(v) for k, v in p.items()}


def mp_reference(p, idx):
    """Growth rate by mpmath.eig of the Jacobian and verdict by the Hurwitz signs (50 digits)."""
    growth, stable = [], []
    with mpmath.workdps(50):
        for i in idx:
            q = point(p, i)
            ev = mpmath.eig(mpmath.matrix(mp_stability.jacobian(**q)), left=False, right=False)
            growth.append(max(z.real for z in ev))
            stable.append(all(h > 0 for h in mp_stability.hurwitz(**q)))
    return growth, np.array(stable)


def rel_error(values, reference, scale):
    return max(
        float(abs(mpmath.mpf(float(v)) - r) / s) for v, r, s in zip(values, reference, scale)
    )


BASELINE = "numpy.linalg.eigvals (baseline)"
EXPANDED = "expanded H3 of Eq. (28)"


def backends():
    """The ``backend=`` values to measure: numba only where it is installed."""
    return ("numba", "numpy") if importlib.util.find_spec("numba") else ("numpy",)


def methods():
    """Name -> (function of a parameter dict returning growth rates or verdicts, kind)."""

    def expanded(q):
        a1, a2, a3, a4 = stability.coefficients(**q)
        H3 = a1 * a2 * a3 - a3**2 - a4 * a1**2
        return (a1 > 0) & (a1 * a2 - a3 > 0) & (H3 > 0) & (a4 * H3 > 0)

    out = {
        BASELINE: (lambda q: np.linalg.eigvals(stability.jacobian(**q)).real.max(axis=-1), "growth")
    }
    for b in backends():
        out[f"stability.growth_rate, {b}"] = (
            lambda q, b=b: stability.growth_rate(**q, backend=b),
            "growth",
        )
        out[f"stability.is_stable, {b}"] = (
            lambda q, b=b: stability.is_stable(**q, backend=b),
            "verdict",
        )
    out[EXPANDED] = (expanded, "verdict")
    return out


@dataclass
class Row:
    """One method: best time, ratio to the baseline, and its errors against mpmath."""

    name: str
    seconds: float
    speedup: float
    growth_error: float  # max relative error of the growth rate (NaN for a sign)
    wrong_random: int  # wrong verdicts on the subsample
    wrong_near: int  # ... 1e-12 (relative) from the boundary
    wrong_stiff: int  # ... stiff tangential modes, 1e-14 from the boundary


def measure(n=10**6, subsample=200, repeat=3, seed=2026, scenario="random"):
    """Time every method on ``n`` points and check it against mpmath (50 digits).

    ``scenario`` is ``"random"`` (`sample`) or ``"map"`` (`sample_map`). The
    baseline's Jacobians are built outside its timed region (for a map they are
    the same 4x4 problems, so its time does not depend on the scenario); numba
    kernels are compiled (or loaded from numba's cache) by a call before theirs.
    The points next to the boundary are random in both scenarios.

    Returns
    -------
    list of Row, baseline first.
    """
    rng = np.random.default_rng(seed)
    p = SCENARIOS[scenario](n, rng)
    n = len(p["Vb"])
    J = stability.jacobian(**p)
    table = methods()
    timed = {BASELINE: best_of(lambda: np.linalg.eigvals(J).real.max(axis=-1), repeat)}
    for name, (fn, _) in table.items():
        if name != BASELINE:
            fn({k: v[:2] if np.ndim(v) else v for k, v in p.items()})  # compile first
            timed[name] = best_of(lambda fn=fn: fn(p), repeat)

    idx = rng.choice(n, subsample, replace=False)
    ref_growth, ref_stable = mp_reference(p, idx)
    scale = [
        max(
            abs(z)
            for z in mpmath.eig(
                mpmath.matrix(mp_stability.jacobian(**point(p, i))), left=False, right=False
            )
        )
        for i in idx
    ]
    m = max(subsample, 20)
    hard = {"near": near_boundary(m, rng), "stiff": near_boundary(m, rng, 1e-14, stiff_sample)}
    exact = {k: mp_reference(b, range(len(b["Vb"])))[1] for k, b in hard.items()}

    def wrong(values, kind, reference):
        stable = values < 0 if kind == "growth" else values
        return int(np.sum(stable != reference))

    rows = []
    for name, (fn, kind) in table.items():
        seconds, values = timed[name]
        err = rel_error(values[idx], ref_growth, scale) if kind == "growth" else float("nan")
        rows.append(
            Row(
                name,
                seconds,
                timed[BASELINE][0] / seconds,
                err,
                wrong(values[idx], kind, ref_stable),
                *(wrong(fn(hard[k]), kind, exact[k]) for k in ("near", "stiff")),
            )
        )
    return rows


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=10**6)
    parser.add_argument("--subsample", type=int, default=200)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--scenario", choices=[*SCENARIOS, "both"], default="both")
    parser.add_argument("--quick", action="store_true", help="n = 20000, subsample 50")
    args = parser.parse_args(argv)
    if args.quick:
        args.n, args.subsample, args.repeat = 20000, 50, 1
    m = max(args.subsample, 20)
    for scenario in SCENARIOS if args.scenario == "both" else [args.scenario]:
        rows = measure(args.n, args.subsample, args.repeat, scenario=scenario)
        print(
            f"\n{scenario}: {args.n} points; errors against mpmath (50 digits) on "
            f"{args.subsample}; {m} points at 1e-12 from the boundary; {m} stiff points "
            "at 1e-14\n"
        )
        print(
            "| method | time [s] | speed-up vs eigvals | max rel. error of growth rate "
            "| wrong verdicts: random | 1e-12 from boundary | stiff, 1e-14 |"
        )
        print("|---|---|---|---|---|---|---|")
        for r in rows:
            err = "-" if np.isnan(r.growth_error) else f"{r.growth_error:.1e}"
            print(
                f"| {r.name} | {r.seconds:.3f} | {r.speedup:.1f}x | {err} | {r.wrong_random} "
                f"| {r.wrong_near} | {r.wrong_stiff} |"
            )


if __name__ == "__main__":
    main()
