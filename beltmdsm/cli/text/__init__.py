"""The readable text of each command's result, and JSON-able values.

Every function takes a result and returns the lines the command prints; none computes.
The result types are imported for the annotations only: a command loads this package
with what it runs, not with every analysis (``sweep`` would otherwise import the
predictions, SciPy's optimizers among them, before its first point).

Modules, one concept each: `beltmdsm.cli.text.common` (JSON-able values, the kinds,
the laws), `.runs` (a run, a sweep, the predictions, the validation), `.periodic`
(periodic responses, cycles, coexistence) and `.continuation` (band, branch, map).
The commands call them through this package (``text.band(...)``).
"""

from .common import jsonable, kind
from .continuation import band, branch, floquet_map
from .periodic import coexistence, cycle, cycle_coexistence, floquet, responses
from .runs import (
    PAPER_STATEMENT,
    peak_verdict,
    prediction,
    simulation,
    spectrum_line,
    sweep,
    sweep_validation,
    validation,
)

__all__ = [
    "jsonable",
    "peak_verdict",
    "spectrum_line",
    "simulation",
    "floquet",
    "cycle",
    "kind",
    "band",
    "responses",
    "branch",
    "coexistence",
    "cycle_coexistence",
    "floquet_map",
    "sweep",
    "sweep_validation",
    "prediction",
    "validation",
    "PAPER_STATEMENT",
]
