"""The runtime's DOP853 step (beltmdsm/oscillator/_stepper.py) ends where it rejects its
least step, whatever the error norm: a finite norm above 1 there once repeated the
rejection forever (a corrector's iterate in a stiff field: tests/beltmdsm/continuation/
test_oscillator_cycle_fold.py, span 0.5, hung for minutes)."""

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]

#: A field whose error estimate stays finite and far above the tolerance at any step.
_CODE = """
import math
import numpy as np
from beltmdsm.oscillator import _stepper

def fun(t, y):
    return np.array([1e200 * math.sin(1e20 * t + y[0])])

y = np.array([0.0])
try:
    _stepper.step(fun, 1.0, y, fun(1.0, y), 1e-3, 2.0, 1e-12, 1e-12, math.inf)
except ArithmeticError as err:
    print(err)
"""


def test_a_rejected_least_step_ends_the_step():
    # a hang is the failure: bounded by the timeout (the step itself takes milliseconds)
    done = subprocess.run([sys.executable, "-c", _CODE], cwd=ROOT, capture_output=True,
                          text=True, timeout=60)  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "no step is accepted past t = 1 s"
