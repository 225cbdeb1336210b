"""beltmdsm: the forced mass on a moving belt of Eq. (4), simulated and analysed.

The runtime of the package: it imports the generated model (``generated/``, written by
``python -m derive`` from derive/), numpy and scipy, never SymPy. Its public API:

* `Model`: a complete, checked parameter set and the model options (contact law,
  tension law); every function below takes one, or the keywords it is built from.
* `SolverSettings`, `simulate`, `Simulation`, `Summary`: one run of Eq. (4) and what it
  says (regime, spectral peaks, energy balance).
* `sweep`, `Sweep`: one parameter over a range, on any executor, with a disk cache.
* `periodic_response`, `floquet`, `periodic_start` (`PeriodicResponse`, `Floquet`,
  `NoPeriodicResponse`): the periodic response, phase-locked ones of ``k`` periods
  too (``periods=k``), and its exact stability; without excitation, the self-excited
  cycle.
* `cycle`, `seed_cycle` (`Cycle`): a self-excited cycle of the model without
  excitation, its period found by shooting with a phase condition, and its seed.
* `floquet_band` (`Band`, `Edge`): the ranges of one parameter where it is unstable,
  each edge with its bifurcation; `branch` (`Branch`): a response continued in one
  parameter through folds, its steps set by `ContinuationSettings` (``settings=`` of
  every continuation); `floquet_map` (`FloquetMap`): the two-parameter map of
  where it is unstable, its boundary curves traced.
* `responses` (`ResponseSet`): every periodic response found at one point, locked
  ones included; `coexistence` (`Coexistence`): where stable responses coexist.
* `lyapunov` (`Lyapunov`): the Lyapunov spectrum of a run through the switches;
  `classify` (`Attractor`): what a run settles on, named (periodic, quasi-periodic,
  chaotic, equilibrium); `basins` (`Basins`): which attractor each start of a plane
  of initial states reaches; `basin_stability` (`BasinStability`): the share of
  random starts in a box that reaches each attractor, with its standard error.
* `predict` (`Prediction`): the unstable belt speeds of the paper's analysis and of a
  consistent MDSM.
* `validate` (`Validation`): the validation of Figs. 2 and 17-21 (``VALIDATION.md``).
* The failures (`beltmdsm.errors`): `BeltmdsmError`, the base of `Refused`,
  `Unsupported`, `StepTooSmall` and `NoPeriodicResponse`.
* ``__version__``: the installed distribution's version.

Subpackages, in the order of their layers (each imports only those before it):
`beltmdsm.model` and `beltmdsm.settings` (the values every function takes),
`beltmdsm.integrate` (the integrators and their compiled kernels), `beltmdsm.run`
(what a run produces: spectra, its summary, modulation), `beltmdsm.simulation`,
`beltmdsm.periodic` (the period map, Newton's method, Floquet, locks),
`beltmdsm.continuation` (edges, branches, bands, two-parameter maps),
`beltmdsm.cycles` (self-excited cycles: shooting, Hopf points, their branches),
`beltmdsm.oscillator` (any derived model of ``generated/models/``: runs, steady sliding
and Hopf points, cycles and forced responses with Floquet multipliers; issue 39),
`beltmdsm.prediction` (the paper's and the consistent MDSM's predictions),
`beltmdsm.attractors` (Lyapunov spectra, the classification of what a run settles on),
`beltmdsm.starts` (where runs and the search for responses start),
`beltmdsm.multistability` (the responses at a point, where stable ones coexist),
`beltmdsm.batch` (sweeps, their rows, table, cache and process pool),
`beltmdsm.basin` (basins of attraction, basin stability),
`beltmdsm.paper_reports` (the validation of the paper's figures, the law comparison,
the contraction evidence), `beltmdsm.cli` (the command line); beside them
`beltmdsm.errors` (the failures) and
`beltmdsm.plotting` (the figures of the results, matplotlib imported when drawing).
The names below are imported when first used, so
that ``import beltmdsm`` and the command line start fast; a type checker reads them
from the stub ``__init__.pyi`` beside this file (the package ships ``py.typed``).
"""

from importlib import import_module
from typing import TYPE_CHECKING

from ._layout import map_siblings
from ._moved import install as install_old_paths

# beltmdsm.generated and beltmdsm.derive: inside an installed package, beside it in a
# source checkout (beltmdsm/_layout.py)
map_siblings(__name__, __path__[0])
# the old paths of the modules that moved (beltmdsm.studies.sweep, ...): the same modules
install_old_paths()

#: Each public name and the module that holds it.
_API = {
    "Model": "model",
    "SolverSettings": "settings",
    "simulate": "simulation",
    "Simulation": "simulation",
    "Summary": "run.summary",
    "sweep": "batch.sweep",
    "Sweep": "batch.sweep",
    "periodic_response": "periodic.shooting",
    "PeriodicResponse": "periodic.response",
    "floquet": "periodic.floquet",
    "Floquet": "periodic.floquet",
    "periodic_start": "starts.forced",
    "cycle": "periodic.cycle",
    "Cycle": "periodic.cycle",
    "seed_cycle": "starts.cycle_seed",
    "floquet_band": "continuation.band",
    "Band": "continuation.band_result",
    "Edge": "continuation.band_result",
    "branch": "branches",
    "Branch": "continuation.branch",
    "ContinuationSettings": "continuation.settings",
    "floquet_map": "continuation.floquet_map",
    "FloquetMap": "continuation.map_result",
    "responses": "multistability.responses",
    "ResponseSet": "multistability.responses",
    "coexistence": "multistability.coexistence",
    "Coexistence": "multistability.coexistence",
    "lyapunov": "attractors.lyapunov",
    "Lyapunov": "attractors.lyapunov",
    "classify": "attractors.classification",
    "Attractor": "attractors.classification",
    "basins": "basin.basins",
    "Basins": "basin.basins",
    "basin_stability": "basin.basin_stability",
    "BasinStability": "basin.basin_stability",
    "predict": "prediction.prediction",
    "Prediction": "prediction.prediction",
    "validate": "paper_reports.validation",
    "Validation": "paper_reports.validation",
    "BeltmdsmError": "errors",
    "Refused": "errors",
    "Unsupported": "errors",
    "StepTooSmall": "errors",
    "NoPeriodicResponse": "errors",
}

#: Written out (not ``list(_API)``), as the stub ``__init__.pyi`` lists them.
__all__ = [
    "Model",
    "SolverSettings",
    "simulate",
    "Simulation",
    "Summary",
    "sweep",
    "Sweep",
    "periodic_response",
    "PeriodicResponse",
    "floquet",
    "Floquet",
    "periodic_start",
    "cycle",
    "Cycle",
    "seed_cycle",
    "floquet_band",
    "Band",
    "Edge",
    "branch",
    "Branch",
    "ContinuationSettings",
    "floquet_map",
    "FloquetMap",
    "responses",
    "ResponseSet",
    "coexistence",
    "Coexistence",
    "lyapunov",
    "Lyapunov",
    "classify",
    "Attractor",
    "basins",
    "Basins",
    "basin_stability",
    "BasinStability",
    "predict",
    "Prediction",
    "validate",
    "Validation",
    "BeltmdsmError",
    "Refused",
    "Unsupported",
    "StepTooSmall",
    "NoPeriodicResponse",
]


def _version() -> str:
    """The installed distribution's version; from a source tree that is not installed,
    pyproject.toml's with a local label (``0.1.0+source``), else ``0+unknown``."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("beltmdsm")
    except PackageNotFoundError:
        import re
        from pathlib import Path

        pyproject = Path(__file__).resolve().parents[1] / "pyproject.toml"
        found = (
            re.search(r'^version = "([^"]+)"', pyproject.read_text(), re.M)
            if pyproject.is_file()
            else None
        )
        return f"{found[1]}+source" if found else "0+unknown"


if not TYPE_CHECKING:  # the stub has none: to a type checker a misspelt name is an error

    def __getattr__(name: str) -> object:
        if name in _API:
            value = getattr(import_module(f".{_API[name]}", __name__), name)
            globals()[name] = value
            return value
        if name == "__version__":  # importlib.metadata costs ~10 ms: read when asked
            globals()[name] = value = _version()
            return value
        raise AttributeError(f"module 'beltmdsm' has no attribute {name!r}")


def __dir__() -> list[str]:
    # the public names only: not the helpers this file imports (TYPE_CHECKING,
    # import_module, map_siblings, install_old_paths) nor the subpackages loaded so far
    return sorted([*__all__, "__version__"])
