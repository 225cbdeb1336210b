"""The names `beltmdsm/__init__.py` imports on first use, as a type checker sees them.

Kept in step with ``_API`` and ``__all__`` there (tests/beltmdsm/test_public_types.py).
A stub, not ``if TYPE_CHECKING:`` imports in the package: the package is the lowest
layer of beltmdsm (tests/test_layers.py), and these names live in every layer above it.
"""

from .attractors.classification import Attractor, classify
from .attractors.lyapunov import Lyapunov, lyapunov
from .basin.basin_stability import BasinStability, basin_stability
from .basin.basins import Basins, basins
from .batch.sweep import Sweep, sweep
from .branches import branch
from .continuation.band import floquet_band
from .continuation.band_result import Band, Edge
from .continuation.branch import Branch
from .continuation.floquet_map import floquet_map
from .continuation.map_result import FloquetMap
from .continuation.settings import ContinuationSettings
from .errors import (
    BeltmdsmError,
    NoPeriodicResponse,
    Refused,
    StepTooSmall,
    Unsupported,
)
from .model import Model
from .multistability.coexistence import Coexistence, coexistence
from .multistability.responses import ResponseSet, responses
from .paper_reports.validation import Validation, validate
from .periodic.cycle import Cycle, cycle
from .periodic.floquet import Floquet, floquet
from .periodic.response import PeriodicResponse
from .periodic.shooting import periodic_response
from .prediction.prediction import Prediction, predict
from .run.summary import Summary
from .settings import SolverSettings
from .simulation import Simulation, simulate
from .starts.cycle_seed import seed_cycle
from .starts.forced import periodic_start

__version__: str
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
