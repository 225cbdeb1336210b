"""Cost of the general Floquet path against the closed-form one (issue 19, item 5).

Times, in one run on one core, after compiling the kernels
(beltmdsm/periodic/closed_form.py: `TangentialMap` is the closed-form path;
beltmdsm/periodic/general_map.py: `GeneralMap` the general one on beltmdsm/periodic/variational.py):

* ``floquet()`` from scratch at belt speeds over [0.5, 12] (the sliding guess, Newton's
  method, and forward iteration where Newton fails), Coulomb friction on the
  closed-form path and on the general one (``engine="general"``), and Stribeck friction
  (mu_k = 0.25, v_s = 1 m/s) on the general path, the only one it has;
* ``floquet()`` continued from the neighbouring response (``guess=``), as a band or a
  branch calls it;
* one application of each period map at a periodic state;
* ``floquet_band(model, "Vb", 0.5, 12)`` (17 points, tol 1e-3) under Coulomb (closed form)
  and Stribeck (general).

and prints the times and their ratios. Run from the repository root:
``python -m benchmarks.bench_general_floquet [--points N]``.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from beltmdsm.continuation.band import floquet_band
from beltmdsm.errors import NoPeriodicResponse
from beltmdsm.model import Model
from beltmdsm.periodic.engines import period_map
from beltmdsm.periodic.floquet import floquet

STRIBECK = dict(friction="stribeck", mu_k=0.25, v_s=1.0)
CASES = (
    ("Coulomb, closed form", {}, None),
    ("Coulomb, general", {}, "general"),
    ("Stribeck, general", STRIBECK, None),
)


def _per_call(fn, values):
    """Mean wall time of ``fn(v)`` over the values [s], and the failures."""
    failed = 0
    clock = time.perf_counter()
    for v in values:
        try:
            fn(v)
        except NoPeriodicResponse:
            failed += 1
    return (time.perf_counter() - clock) / len(values), failed


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points", type=int, default=47, help="belt speeds (default 47)")
    args = parser.parse_args(argv)
    values = np.linspace(0.5, 12.0, args.points)
    for _, law, engine in CASES:  # compile and cache every kernel first
        floquet(Model(Vb=5.0, **law), engine=engine)
    times = {}
    for name, law, engine in CASES:
        scratch, failed = _per_call(
            lambda v, law=law, engine=engine: floquet(Model(Vb=v, **law), engine=engine), values
        )
        previous = {}

        def continued(v, law=law, engine=engine, previous=previous):
            f = floquet(Model(Vb=v, **law), engine=engine, guess=previous.get("r"), forward=0)
            previous["r"] = f.response

        floquet(Model(Vb=values[0], **law), engine=engine)
        neighbour, _ = _per_call(continued, values)
        f = floquet(Model(Vb=5.0, **law), engine=engine)
        pmap = period_map(f.response.model, engine=engine)
        x = f.response.shooting_state
        one, _ = _per_call(lambda _v, pmap=pmap, x=x: pmap(x), range(200))
        times[name] = (scratch, neighbour, one)
        print(
            f"{name:22s} floquet() from scratch {1e3 * scratch:7.2f} ms ({failed} of "
            f"{values.size} without a response), continued {1e3 * neighbour:7.2f} ms, "
            f"one period map {1e3 * one:6.3f} ms"
        )
    ref = times[CASES[0][0]]
    for name, t in list(times.items())[1:]:
        print(
            f"{name}: {t[0] / ref[0]:.1f}x from scratch, {t[1] / ref[1]:.1f}x continued, "
            f"{t[2] / ref[2]:.1f}x per period map, against the closed form"
        )
    bands = {}
    for name, law in (("Coulomb (closed form)", {}), ("Stribeck (general)", STRIBECK)):
        clock = time.perf_counter()
        band = floquet_band(Model(**law), "Vb", 0.5, 12.0)
        bands[name] = time.perf_counter() - clock
        print(
            f"floquet_band Vb 0.5..12, {name}: {bands[name]:.2f} s, {len(band.grid)} "
            f"responses, unstable {[[round(a, 4), round(b, 4)] for a, b in band.unstable]}"
        )
    a, b = bands.values()
    print(f"band under Stribeck: {b / a:.1f}x the Coulomb band's time")


if __name__ == "__main__":
    main()
