"""The compiles of the normal motion's integrator: one per contact law, against one per
friction and contact law (the named baseline).

The normal motion (beltmdsm/integrate/normal.py) binds its surface kernels with one
friction law (`beltmdsm.integrate.normal.NORMAL_FRICTION`): its compiled integrator is
the same under every friction law. The baseline binds each model's own friction law,
as the normal motion did before: a kernel set, and so a compile, per friction and
contact law. Both are compiled here (``backend="numba"``, in the foreground) with cold
caches, in one process each (``NUMBA_CACHE_DIR`` and ``BELTMDSM_CACHE`` in a new
temporary folder), over every friction law and the contact laws asked for; then again
with the caches those processes filled (warm: loaded from numba's disk cache).

Prints, for each side, the integrators compiled, the CPU seconds of the process, cold
and warm, and the ratio baseline / ours.

Usage: python -m benchmarks.bench_normal_compile [--quick]  (``--quick``: one contact law)
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile

CODE = """
import itertools, sys
import numpy as np
from beltmdsm import Model
from beltmdsm.generated import hybrid
from beltmdsm.generated.capabilities import CAPABILITIES
from beltmdsm.integrate import _compiled
from beltmdsm.integrate.normal import NORMAL_FRICTION
ours, contacts = sys.argv[1] == "ours", sys.argv[2].split(",")
frictions = sorted({f for f, _, _ in CAPABILITIES})
made = set()
for friction, contact in itertools.product(frictions, contacts):
    model = Model(friction=friction, contact=contact)
    laws = {"friction": NORMAL_FRICTION} if ours else {}
    field = hybrid.bind_response_field(
        backend="python", **model.arguments(hybrid.bind_response_field)).args
    surfaces, rates = (
        bind(backend="python", **{**model.arguments(bind), **laws}).args
        for bind in (hybrid.bind_surfaces, hybrid.bind_surface_rates)
    )
    lazy = _compiled.advance("response_field", model, "numba", **laws)
    # compiled for the types of NormalMotion's call
    lazy.compiled((field, surfaces, rates, -1.0, np.array([3]), np.array([1.0]), 0.0,
                   np.zeros(4), 1.0, 0.0, 1e-10, 1e-10, 0.1, 10))
    made.add(lazy.stem)
print(len(made))
"""


def _run(side: str, contacts: str, cache: str) -> tuple[int, float]:
    """The integrators ``side`` compiles and the CPU seconds of its process."""
    env = {**os.environ, "NUMBA_CACHE_DIR": os.path.join(cache, "numba"), "BELTMDSM_CACHE": cache}
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run(
        [sys.executable, "-c", CODE, side, contacts],
        env=env,
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
    return int(out.split()[-1]), cpu


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="one contact law")
    args = parser.parse_args()
    from beltmdsm.generated.capabilities import CAPABILITIES

    contacts = sorted({c for _, c, _ in CAPABILITIES})[: 1 if args.quick else None]
    times = {}
    for side in ("baseline", "ours"):
        with tempfile.TemporaryDirectory(prefix="beltmdsm-bench-") as cache:
            n, cold = _run(side, ",".join(contacts), cache)
            _, warm = _run(side, ",".join(contacts), cache)
        times[side] = (cold, warm)
        print(f"{side:8s}: {n} integrators compiled; CPU cold {cold:6.1f} s, warm {warm:5.1f} s")
    (bc, bw), (oc, ow) = times["baseline"], times["ours"]
    print(f"baseline / ours: cold {bc / oc:.2f}x, warm {bw / ow:.2f}x (contacts: {contacts})")


if __name__ == "__main__":
    main()
