"""Moved (issue 38) to `beltmdsm.continuation.linear_verdict`:
the paper's linear verdict on the rows of a Floquet map.

This path is that module itself (its names, private ones included, and what a test
patches in it).
"""

import sys

from . import linear_verdict as _moved
from .linear_verdict import *  # noqa: F403  (the names, for type checkers)

sys.modules[__name__] = _moved
