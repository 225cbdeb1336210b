"""Moved (issue 38) to `beltmdsm.periodic.normal_orbit`:
the periodic orbit of the normal motion (normal_orbit).

This path is that module itself (its names, private ones included, and what a test
patches in it).
"""

import sys

from . import normal_orbit as _moved
from .normal_orbit import *  # noqa: F403  (the names, for type checkers)

sys.modules[__name__] = _moved
