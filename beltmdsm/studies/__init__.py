"""Old home of the studies, now cut by role (issue 38); its paths still import.

Where each module went (`beltmdsm._moved.MOVED`):

* the batch engine, `beltmdsm.batch`: ``sweep``, ``row``, ``table``, ``cache``, ``pool``;
* the responses at a point and where stable ones coexist, `beltmdsm.multistability`:
  ``responses``, ``coexistence``, ``cycle_coexistence``, ``overlay`` (now
  ``stable_ranges``);
* the starting states, `beltmdsm.starts`: ``seeds`` (with ``beltmdsm.periodic.start``);
* basins of attraction, `beltmdsm.basin`: ``basins``, ``basin_stability``,
  ``basin_stability_along``, ``self_excited_basins``;
* the paper's reports, `beltmdsm.paper_reports`: ``validation``, ``law_comparison``,
  ``evidence`` (now ``contraction_evidence``).

``import beltmdsm.studies.sweep`` and ``beltmdsm.studies.sweep`` give the module at its
new path (the same object) with a `DeprecationWarning` naming it.

Examples
--------
>>> import warnings
>>> import beltmdsm.studies
>>> with warnings.catch_warnings():
...     warnings.simplefilter("ignore", DeprecationWarning)
...     print(beltmdsm.studies.validation.__name__)
beltmdsm.paper_reports.validation
"""

from importlib import import_module

from .._moved import MOVED


def __getattr__(name: str) -> object:
    # ``beltmdsm.studies.sweep`` without an import statement: the finder warns
    if f"{__name__}.{name}" in MOVED:
        return import_module(f"{__name__}.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(k.rpartition(".")[2] for k in MOVED if k.startswith(__name__ + "."))
