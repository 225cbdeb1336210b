"""Speed against error of the stability functions (issue: forced system, item 6).

On N random parameter points (default 10^6, around the paper's base set, Vb up to
1.4 Vhat) it times, in one run:

* ``stability.is_stable``     (factored Routh-Hurwitz, a sign per point)
* ``stability.growth_rate``   (closed-form roots of the two quadratics)
* ``numpy.linalg.eigvals``    of the same Jacobians ``stability.jacobian`` (the baseline;
  the Jacobians are built outside the timed region)
* the expanded ``H3 = a1 a2 a3 - a3^2 - a4 a1^2`` of Eq. (28) from ``stability.coefficients``

and prints each time, its ratio to the baseline, and its error against mpmath at 50
digits on a subsample (``mpmath.eig`` of the Jacobian for growth rates, the Hurwitz
signs for verdicts), plus the verdict errors on points 1e-12 (relative) from the
stability boundary, and 1e-14 from it for stiff tangential modes. Run from the repository root:
``python -m benchmarks.bench_stability [--n N] [--quick]``.
"""
from __future__ import annotations

import argparse
import time

import mpmath
import numpy as np

from generated import friction, stability
from generated.mp import stability as mp_stability
from generated.parameters import BASE

MODEL = ("beta1", "omega1", "beta2", "omega2", "alpha", "Omega", "mu_s", "g")


def sample(n, rng):
    p = {k: BASE[k] * np.exp(rng.uniform(-np.log(3), np.log(3), n)) for k in MODEL}
    p["Vhat"] = friction.vhat(**p)
    p["Vb"] = p["Vhat"] * rng.uniform(0.0, 1.4, n)
    return p


def stiff_sample(n, rng):
    """A stiff, lightly damped tangential mode next to a heavily damped normal one:
    where the expanded H3 cancels most (see tests/test_stability.py)."""
    p = sample(n, rng)
    p["omega1"] = 10**rng.uniform(1.5, 2.5, n)
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
    return {k: float(v[i]) for k, v in p.items()}


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
    return max(float(abs(mpmath.mpf(float(v)) - r) / s)
               for v, r, s in zip(values, reference, scale))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=10**6)
    parser.add_argument("--subsample", type=int, default=200)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--quick", action="store_true", help="n = 20000, subsample 50")
    args = parser.parse_args(argv)
    if args.quick:
        args.n, args.subsample, args.repeat = 20000, 50, 1
    rng = np.random.default_rng(2026)
    p = sample(args.n, rng)
    J = stability.jacobian(**p)

    t_eig, lam = best_of(lambda: np.linalg.eigvals(J), args.repeat)
    t_growth, growth = best_of(lambda: stability.growth_rate(**p), args.repeat)
    t_stable, stable = best_of(lambda: stability.is_stable(**p), args.repeat)

    def expanded():
        a1, a2, a3, a4 = stability.coefficients(**p)
        H3 = a1 * a2 * a3 - a3**2 - a4 * a1**2
        return (a1 > 0) & (a1 * a2 - a3 > 0) & (H3 > 0) & (a4 * H3 > 0)

    t_expanded, stable_expanded = best_of(expanded, args.repeat)

    idx = rng.choice(args.n, args.subsample, replace=False)
    ref_growth, ref_stable = mp_reference(p, idx)
    scale = [max(abs(z) for z in mpmath.eig(mpmath.matrix(mp_stability.jacobian(**point(p, i))),
                                            left=False, right=False)) for i in idx]
    eig_growth = lam.real.max(axis=-1)
    rows = [
        ("numpy.linalg.eigvals (baseline)", t_eig, rel_error(eig_growth[idx], ref_growth, scale),
         int(np.sum((eig_growth[idx] < 0) != ref_stable))),
        ("stability.growth_rate", t_growth, rel_error(growth[idx], ref_growth, scale),
         int(np.sum((growth[idx] < 0) != ref_stable))),
        ("stability.is_stable", t_stable, float("nan"), int(np.sum(stable[idx] != ref_stable))),
        ("expanded H3 of Eq. (28)", t_expanded, float("nan"),
         int(np.sum(stable_expanded[idx] != ref_stable))),
    ]

    def wrong_verdicts(b):
        _, exact = mp_reference(b, range(len(b["Vb"])))
        a1, a2, a3, a4 = stability.coefficients(**b)
        H3 = a1 * a2 * a3 - a3**2 - a4 * a1**2
        return {
            "numpy.linalg.eigvals (baseline)": int(np.sum(
                (np.linalg.eigvals(stability.jacobian(**b)).real.max(axis=-1) < 0) != exact)),
            "stability.growth_rate": int(np.sum((stability.growth_rate(**b) < 0) != exact)),
            "stability.is_stable": int(np.sum(stability.is_stable(**b) != exact)),
            "expanded H3 of Eq. (28)": int(np.sum(((H3 > 0) & (a1 > 0)) != exact)),
        }

    m = max(args.subsample, 20)
    near = wrong_verdicts(near_boundary(m, rng))
    stiff = wrong_verdicts(near_boundary(m, rng, 1e-14, stiff_sample))

    print(f"{args.n} points; errors against mpmath (50 digits) on {args.subsample}; "
          f"{m} points at 1e-12 from the boundary; {m} stiff points at 1e-14\n")
    print("| method | time [s] | speed-up vs eigvals | max rel. error of growth rate "
          "| wrong verdicts: random | 1e-12 from boundary | stiff, 1e-14 |")
    print("|---|---|---|---|---|---|---|")
    for name, t, err, wrong in rows:
        err_s = "-" if np.isnan(err) else f"{err:.1e}"
        print(f"| {name} | {t:.3f} | {t_eig / t:.1f}x | {err_s} | {wrong} | {near[name]} "
              f"| {stiff[name]} |")


if __name__ == "__main__":
    main()
