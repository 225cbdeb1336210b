"""Another model's cycles born at a Hopf point (issue 39): the walk on the one driver
against the natural-parameter stepping it replaced, on the same branch.

* **baseline** (natural stepping, `beltmdsm.oscillator.hopf_branch` before issue 39's
  cycle problem, copied here): from the same seed, each cycle shot at the next value
  of the parameter from the last (`beltmdsm.oscillator.slip_shooting._shoot_slip`,
  its own damped Newton's method with the monodromy), a step of 2 % of the span,
  halved where the shooting fails and grown by 1.5 where it succeeds, to where it
  fails at an eighth of that; then the onset of stick by the secant of the least slip
  speed (`beltmdsm.oscillator.onset.stick_onset`) from the cycle four steps back.
* **ours**: `beltmdsm.oscillator.hopf_branch.hopf_branch`, the same seed walked by
  pseudo-arclength on the one driver
  (`beltmdsm.continuation.oscillator_cycle.OscillatorCycleProblem`), the onset located
  on the way.

Printed per branch: the cycles each returns, the CPU seconds of the walk (the seed's
shooting excluded: both share it), per cycle, their ratio, and the two onsets' difference.
CPU time (``time.process_time``) of this process, with ``uptime`` before and after: on
a loaded machine the wall time is not the cost.

Run from the repository root: ``python -m benchmarks.bench_oscillator_cycle_branch``.
"""

from __future__ import annotations

import os
import time

from beltmdsm.errors import NoPeriodicResponse
from beltmdsm.oscillator import System, hopf_points, steady_sliding
from beltmdsm.oscillator import hopf_branch as hb
from beltmdsm.oscillator.onset import stick_onset
from beltmdsm.oscillator.slip_shooting import _shoot_slip

#: (model, law, parameters, swept parameter, its range, span)
BRANCHES = (
    ("belt_1dof", "stribeck", {}, "Vb", (0.5, 5.0), 4.5),
    ("hoffmann", "stribeck", {}, "Vb", (0.2, 8.0), 0.3),
)


def _seed(system, param, hopf, span):
    eq_above = steady_sliding(system.replace(**{param: hopf + 0.01 * span}))
    side = 1 if eq_above.stable else -1
    for frac in hb._OFFSETS:
        seed = hb._seed(system, param, hopf + side * frac * span)
        if seed is not None:
            return side, seed
    raise NoPeriodicResponse("no seed")


def natural(seed, param, side, span):
    """The baseline (module docstring): the cycles and the onset."""
    cycles = [seed]
    h = h_max = side * 0.02 * span
    h_min = h_max / 8
    last = seed
    for _ in range(200):
        value = last.system.params[param] + h
        try:
            last = _shoot_slip(last.system.replace(**{param: float(value)}), last.state,
                               last.period, 30, dict(rtol=1e-11, atol=1e-11))  # fmt: skip
        except NoPeriodicResponse:
            if abs(h) <= abs(h_min):
                break
            h = 0.5 * h
            continue
        cycles.append(last)
        h = side * min(abs(h_max), 1.5 * abs(h))
    onset = stick_onset(cycles[max(0, len(cycles) - 4)], param, h_max)
    return cycles + [onset], onset


def main() -> None:
    print("uptime:", os.popen("uptime").read().strip())
    for model, law, params, param, (lo, hi), span in BRANCHES:
        s = System(model, friction=law, **params)
        (hopf,) = hopf_points(s, param, lo, hi)
        side, seed = _seed(s, param, float(hopf), span)
        t0 = time.process_time()
        old, old_onset = natural(seed, param, side, span)
        t_old = time.process_time() - t0
        t0 = time.process_time()
        new = hb.hopf_branch(s, param, float(hopf), span)
        t_new = time.process_time() - t0  # includes its own seed (shot again)
        t0 = time.process_time()
        _seed(s, param, float(hopf), span)
        t_seed = time.process_time() - t0
        t_new -= t_seed
        a, b = old_onset.system.params[param], new.onset.system.params[param]
        print(
            f"{model} ({law}) in {param}, Hopf {float(hopf):.8g}: natural stepping "
            f"{len(old)} cycles, {t_old:.2f} s CPU ({t_old / len(old):.3f} s a cycle); "
            f"driver {len(new.cycles)} cycles, {t_new:.2f} s CPU "
            f"({t_new / len(new.cycles):.3f} s a cycle); per cycle driver / natural "
            f"{t_new / len(new.cycles) / (t_old / len(old)):.2f}, whole walk "
            f"{t_new / t_old:.2f}; onsets {a:.12g} and {b:.12g} (differ by {abs(a - b):.1e}); "
            f"seed {t_seed:.2f} s"
        )
    print("uptime:", os.popen("uptime").read().strip())


if __name__ == "__main__":
    main()
