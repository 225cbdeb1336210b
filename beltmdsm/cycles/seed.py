"""Moved (issue 38) to `beltmdsm.periodic.cycle_seed`:
the seed of a self-excited cycle.

A periodic orbit of a model without excitation belongs with the other periodic orbits,
below the continuation that follows it (tests/test_layers.py). This path is that module
itself (its names, private ones included, and what a test patches in it).
"""

import sys

from ..periodic import cycle_seed as _moved
from ..periodic.cycle_seed import *  # noqa: F403  (the names, for type checkers)

sys.modules[__name__] = _moved
