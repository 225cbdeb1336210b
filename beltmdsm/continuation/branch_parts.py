"""Moved (issue 38) to `beltmdsm.continuation.branch_result`:
the result of a branch (Branch, its special points and parts).

This path is that module itself (its names, private ones included, and what a test
patches in it).
"""

import sys

from . import branch_result as _moved
from .branch_result import *  # noqa: F403  (the names, for type checkers)

sys.modules[__name__] = _moved
