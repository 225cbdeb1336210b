"""Speed against error of the Lyapunov spectrum and the rotation number (issue 31, item 6).

* **Exponents against run length**: on stable periodic responses of the base set (with
  reversals at Vb = 2; with a stick phase at Vb = 0.1, alpha = 0.05) the spectrum of
  `beltmdsm.attractors.lyapunov.lyapunov` started on the orbit, for run lengths from 100 s
  up, against the exact ``ln |mu_i| / T`` of its Floquet multipliers: the time, the
  largest error over the finite exponents, and the error the method states.
* **Rotation number against samples**: on an invariant circle with a known irrational
  rotation number (the golden mean, drawn through a nonlinear conjugacy), the weighted
  Birkhoff average of `beltmdsm.attractors.classification.rotation_number` against the plain
  mean of the angle increments (the baseline), by the number of samples (map iterates).

Run from the repository root: ``python -m benchmarks.bench_lyapunov``.
"""

from __future__ import annotations

import time

import numpy as np

from beltmdsm import Model
from beltmdsm.attractors.classification import rotation_number
from beltmdsm.attractors.lyapunov import lyapunov
from beltmdsm.periodic.floquet import floquet

ORBITS = {"reversals (Vb=2)": dict(Vb=2.0), "stick (Vb=0.1, alpha=0.05)": dict(Vb=0.1, alpha=0.05)}


def exponents() -> None:
    print("Lyapunov exponents against run length (reference: ln|mu|/T of Floquet)")
    print(f"  {'orbit':28s} {'t_end [s]':>9s} {'time [s]':>9s} {'max error':>10s} {'stated':>10s}")
    for name, params in ORBITS.items():
        f = floquet(Model(**params))
        mu = np.sort(np.abs(f.multipliers))[::-1]
        finite = mu > 1e-12 * mu[0]
        ref = np.log(mu[finite]) / f.response.period
        lyapunov(f.response.model, y0=f.response.state0, t_end=60.0, t_transient=0.0)  # compile
        for t_end in (60.0, 120.0, 240.0, 480.0, 960.0):
            t0 = time.perf_counter()
            s = lyapunov(f.response.model, y0=f.response.state0, t_end=t_end, t_transient=0.0)
            dt = time.perf_counter() - t0
            err = float(np.max(np.abs(s.exponents[: finite.sum()] - ref)))
            stated = float(np.max(s.error[: finite.sum()]))
            print(f"  {name:28s} {t_end:9.0f} {dt:9.2f} {err:10.2e} {stated:10.2e}")


def rotation() -> None:
    rho = (np.sqrt(5) - 1) / 2 - 1
    print("Rotation number against samples (golden mean on a conjugated circle)")
    print(f"  {'samples':>8s} {'weighted error':>15s} {'stated':>10s} {'plain mean error':>17s}")
    for n in (64, 128, 256, 512, 1024, 2048):
        th = 2 * np.pi * (0.3 + rho * np.arange(n))
        u = th + 0.3 * np.sin(th)
        y = np.column_stack([4 + 2 * np.cos(u), -6 + 0.5 * np.sin(u) + 0.3 * np.cos(u)])
        r, acc = rotation_number(y)
        w = y - y.mean(axis=0)
        plain = np.mean(np.angle(np.exp(1j * np.diff(np.arctan2(w[:, 1], w[:, 0]))))) / (2 * np.pi)
        print(f"  {n:8d} {abs(r - rho):15.2e} {acc:10.2e} {abs(plain - rho):17.2e}")


if __name__ == "__main__":
    exponents()
    rotation()
