"""A 1000 s run of belt_1dof by the generic runtime against one of the paper's model
(issue 39, item 4: "a 1000 s run of belt_1dof costs no more than one of paper").

The same oscillation on both sides: Stribeck friction without excitation at Vb = 1.5
(the base set's omega1, beta1, g, mu_s, mu_k, v_s), its stick-slip cycle, sampled every
0.02 s, tolerances 1e-10:

* **belt_1dof**, `beltmdsm.oscillator.simulate` on the model module (the generated
  ``beltmdsm.generated.models.belt_1dof``, or, until it is generated, the hand-typed
  reference of the tests, tests/beltmdsm/oscillator/reference_belt_1dof.py, said in
  the output), with numba (its integrator and kernels compiled, cached on disk) and in
  plain Python;
* **paper**, `beltmdsm.simulate` with ``alpha = 0`` (its compiled integrator).

Times: **cold**, a fresh process (import, the compiled code loaded from numba's disk
cache, the run), the median of ``--repeat`` processes; **warm**, the median of
``--repeat`` runs in one process. Prints each time and the ratios belt_1dof / paper.
Run from the repository root: ``python -m benchmarks.bench_oscillator [--repeat N]``.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import time

T_END = 1000.0
PAPER = (
    "import beltmdsm; "
    "beltmdsm.simulate(beltmdsm.Model(friction='stribeck', alpha=0.0, Vb=1.5), t_end=1000.0)"
)
MODEL = """
import sys
sys.path.insert(0, 'tests/beltmdsm/oscillator')
from beltmdsm.oscillator import System, simulate
try:
    from beltmdsm.generated.models import belt_1dof as module
except ImportError:
    import reference_belt_1dof as module
s = System(module, friction='stribeck', Vb=1.5)
run = simulate(s, 1000.0, backend={backend!r})
"""


def _cold(code: str, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        subprocess.run([sys.executable, "-c", code], check=True)
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def _warm(fn, repeat: int) -> float:
    fn()
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    sys.path.insert(0, "tests/beltmdsm/oscillator")
    import beltmdsm
    from beltmdsm.oscillator import System, simulate

    try:
        from beltmdsm.generated.models import belt_1dof as module

        source = "beltmdsm.generated.models.belt_1dof"
    except ImportError:
        import reference_belt_1dof as module

        source = "the tests' hand-typed reference (no generated belt_1dof yet)"
    s = System(module, friction="stribeck", Vb=1.5)
    print(f"belt_1dof: {source}; 1000 s, Stribeck, Vb = 1.5, dt = 0.02 s")
    for backend in ("numba", "python"):
        simulate(s, 10.0, backend=backend)  # compiled (or loaded) before the cold runs
    paper_w = _warm(
        lambda: beltmdsm.simulate(
            beltmdsm.Model(friction="stribeck", alpha=0.0, Vb=1.5), t_end=T_END
        ),
        args.repeat,
    )
    model_w = _warm(lambda: simulate(s, T_END, backend="numba"), args.repeat)
    python_w = _warm(lambda: simulate(s, T_END, backend="python"), 1)
    paper_c = _cold(PAPER, args.repeat)
    model_c = _cold(MODEL.format(backend="numba"), args.repeat)
    print(f"paper     warm {paper_w:8.3f} s   cold {paper_c:8.3f} s")
    print(f"belt_1dof warm {model_w:8.3f} s   cold {model_c:8.3f} s   (numba)")
    print(f"belt_1dof warm {python_w:8.3f} s   (plain Python)")
    print(f"ratio belt_1dof / paper: warm {model_w / paper_w:.2f}, cold {model_c / paper_c:.2f}")


if __name__ == "__main__":
    main()
