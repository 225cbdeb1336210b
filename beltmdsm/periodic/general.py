"""Moved (issue 38) to `beltmdsm.periodic.general_map`:
the general period map (GeneralMap, engine 'general').

This path is that module itself (its names, private ones included, and what a test
patches in it).
"""

import sys

from . import general_map as _moved
from .general_map import *  # noqa: F403  (the names, for type checkers)

sys.modules[__name__] = _moved
