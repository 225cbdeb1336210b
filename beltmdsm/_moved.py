"""The old import paths of modules that moved (issue 38), each kept as the new module.

``import beltmdsm.studies.sweep`` (or ``beltmdsm.periodic.start``, ...) still works: a
finder on ``sys.meta_path`` answers an old name with the module now holding it (the same
module object, so that its classes, its private names and a test's monkeypatch are one),
and warns once per old name with a `DeprecationWarning` naming the new path. A package
that moved (``beltmdsm.studies.validation``) moves with its submodules. Nothing is
imported here until an old name is asked for, so ``import beltmdsm`` stays fast.

Examples
--------
>>> import sys, warnings
>>> _ = sys.modules.pop("beltmdsm.studies.sweep", None)  # warned once per process
>>> with warnings.catch_warnings(record=True) as caught:
...     warnings.simplefilter("always")
...     from beltmdsm.studies.sweep import sweep
>>> sweep.__module__, caught[0].category.__name__
('beltmdsm.batch.sweep', 'DeprecationWarning')
>>> print(caught[0].message)
beltmdsm.studies.sweep moved to beltmdsm.batch.sweep (issue 38); import it from there
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
import sys
import warnings
from types import ModuleType

__all__ = ["MOVED", "new_name", "install"]

#: Each old module path and the module that holds its names now.
MOVED = {
    # the batch engine: one parameter over a range, cached, on any executor
    "beltmdsm.studies.sweep": "beltmdsm.batch.sweep",
    "beltmdsm.studies.row": "beltmdsm.batch.row",
    "beltmdsm.studies.table": "beltmdsm.batch.table",
    "beltmdsm.studies.cache": "beltmdsm.batch.cache",
    "beltmdsm.studies.pool": "beltmdsm.batch.pool",
    # the responses that exist and coexist at a point and over a range
    "beltmdsm.studies.responses": "beltmdsm.multistability.responses",
    "beltmdsm.studies.coexistence": "beltmdsm.multistability.coexistence",
    "beltmdsm.studies.cycle_coexistence": "beltmdsm.multistability.cycle_coexistence",
    "beltmdsm.studies.overlay": "beltmdsm.multistability.stable_ranges",
    # starting states, one package (its modules at their own layers)
    "beltmdsm.studies.seeds": "beltmdsm.starts.forced",
    "beltmdsm.periodic.start": "beltmdsm.starts.forced",
    "beltmdsm.periodic.cycle_seed": "beltmdsm.starts.cycle_seed",
    # basins of attraction and basin stability
    "beltmdsm.studies.basins": "beltmdsm.basin.basins",
    "beltmdsm.studies.basin_stability": "beltmdsm.basin.basin_stability",
    "beltmdsm.studies.basin_stability_along": "beltmdsm.basin.basin_stability_along",
    "beltmdsm.studies.self_excited_basins": "beltmdsm.basin.self_excited_basins",
    # the paper's reports
    "beltmdsm.studies.validation": "beltmdsm.paper_reports.validation",
    "beltmdsm.studies.law_comparison": "beltmdsm.paper_reports.law_comparison",
    "beltmdsm.studies.evidence": "beltmdsm.paper_reports.contraction_evidence",
    # renamed for what they hold
    "beltmdsm.attractors.landing": "beltmdsm.attractors.recurrence",
    "beltmdsm.integrate._superpose": "beltmdsm.integrate._switch_scan",
    # issue 38's continuation core: the self-excited cycle's finder is a periodic orbit,
    # below the continuation that follows it; modules renamed for what they hold
    "beltmdsm.cycles.cycle": "beltmdsm.periodic.cycle",
    "beltmdsm.cycles.flow": "beltmdsm.periodic.cycle_flow",
    "beltmdsm.cycles.returns": "beltmdsm.periodic.cycle_returns",
    "beltmdsm.cycles.seed": "beltmdsm.starts.cycle_seed",
    "beltmdsm.continuation.branch_parts": "beltmdsm.continuation.branch_result",
    "beltmdsm.continuation.map_linear": "beltmdsm.continuation.linear_verdict",
    "beltmdsm.continuation.arclength": "beltmdsm.continuation.forced",
    "beltmdsm.periodic.general": "beltmdsm.periodic.general_map",
    "beltmdsm.periodic.normal": "beltmdsm.periodic.normal_orbit",
    "beltmdsm.periodic.tangential": "beltmdsm.periodic.closed_form",
}


def new_name(name: str) -> str | None:
    """The module that holds ``name``'s names now, or None where it did not move.

    >>> new_name("beltmdsm.studies.validation.cases")
    'beltmdsm.paper_reports.validation.cases'
    >>> new_name("beltmdsm.batch.sweep") is None
    True
    """
    head = name
    while head:
        if head in MOVED:
            return MOVED[head] + name[len(head) :]
        head = head.rpartition(".")[0]
    return None


class _OldPaths(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Finds an old path and loads it as the module that holds its names now."""

    def find_spec(self, name, path=None, target=None):  # noqa: ARG002 - the finder protocol
        new = new_name(name)
        return None if new is None else importlib.util.spec_from_loader(name, self)

    def create_module(self, spec) -> ModuleType:
        new = new_name(spec.name)
        warnings.warn(
            f"{spec.name} moved to {new} (issue 38); import it from there",
            DeprecationWarning,
            stacklevel=2,
        )
        # the module itself: its attributes keep their own names (importlib sets
        # __spec__ and __name__ only where they are missing)
        return importlib.import_module(new)

    def exec_module(self, module: ModuleType) -> None:
        pass  # already executed under its new name


def install() -> None:
    """Put the finder first on ``sys.meta_path`` (once): before the path finder, which
    would load a second copy of a moved package's submodule under its old name."""
    if not any(isinstance(f, _OldPaths) for f in sys.meta_path):
        sys.meta_path.insert(0, _OldPaths())
