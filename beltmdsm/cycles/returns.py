"""Moved (issue 38) to `beltmdsm.periodic.cycle_returns`:
returns to a section and the run's step of a model without excitation.

A periodic orbit of a model without excitation belongs with the other periodic orbits,
below the continuation that follows it (tests/test_layers.py). This path is that module
itself (its names, private ones included, and what a test patches in it).
"""

import sys

from ..periodic import cycle_returns as _moved
from ..periodic.cycle_returns import *  # noqa: F403  (the names, for type checkers)

sys.modules[__name__] = _moved
