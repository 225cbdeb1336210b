"""Starting states: where runs, the searches for responses and shooting start (issue 38).

* `beltmdsm.starts.forced`: the forced model's starts. `periodic_start` (a state on the
  periodic response, ``simulate --start periodic``), the stroboscope of a run from rest
  (`run_stroboscope`), ladders continued on the period map (`ladder`) and Newton's
  method from a sample (`shoot`): what `beltmdsm.multistability` seeds its searches with.
* `beltmdsm.starts.cycle_seed`: the seed of a self-excited cycle (`seed_cycle`), a run
  off unstable steady sliding read on the section, and the edge of the friction cone
  where a stick ends (`stick_end`).

The two sit at their own layers (tests/test_layers.py): `cycle_seed` at the periodic
orbits' (`beltmdsm.periodic.cycle` shoots from it), `forced` above `beltmdsm.simulation`
(it runs it). So this file imports neither when it is loaded: importing
``beltmdsm.starts.cycle_seed`` loads no simulation. Their public names are read here on
first use (``from beltmdsm.starts import periodic_start``, as before the split).

Examples
--------
>>> import beltmdsm.starts
>>> beltmdsm.starts.periodic_start.__module__, beltmdsm.starts.seed_cycle.__module__
('beltmdsm.starts.forced', 'beltmdsm.starts.cycle_seed')
"""

from importlib import import_module
from typing import TYPE_CHECKING

#: The modules whose public names (their ``__all__``) this package gives, the lower first.
_MODULES = ("cycle_seed", "forced")

if TYPE_CHECKING:
    from .cycle_seed import *  # noqa: F403
    from .forced import *  # noqa: F403
else:

    def __getattr__(name: str) -> object:
        # a dunder (``__path__``, doctest's ``__test__``) is no public name: asked for
        # while this file loads, an import here would recurse
        for stem in () if name.startswith("__") else _MODULES:
            module = import_module(f".{stem}", __package__)
            if name in module.__all__:
                return getattr(module, name)
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted({n for s in _MODULES for n in import_module(f".{s}", __package__).__all__})
