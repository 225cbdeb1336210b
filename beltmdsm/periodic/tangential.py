"""Moved (issue 38) to `beltmdsm.periodic.closed_form`:
the closed-form period map (ClosedFormMap, engine 'closed_form'; TangentialMap before).

This path is that module itself (its names, private ones included, and what a test
patches in it).
"""

import sys

from . import closed_form as _moved
from .closed_form import *  # noqa: F403  (the names, for type checkers)

sys.modules[__name__] = _moved
