"""Moved (issue 38) to `beltmdsm.periodic.cycle`:
the self-excited cycle by shooting with a phase condition, a periodic orbit.

A periodic orbit of a model without excitation belongs with the other periodic orbits,
below the continuation that follows it (tests/test_layers.py). This path is that module
itself (its names, private ones included, and what a test patches in it).
"""

import sys

from ..periodic import cycle as _moved
from ..periodic.cycle import *  # noqa: F403  (the names, for type checkers)

sys.modules[__name__] = _moved
