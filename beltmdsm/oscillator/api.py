"""The public API on another model than the paper's: ``beltmdsm.simulate(Model(model=
"belt_1dof", ...))`` and the other analyses of `beltmdsm.model.GENERIC` come here.

Each public function of the paper's model hands a `beltmdsm.model.OtherModel` to its
twin below, which builds the model's `System` and runs the generic runtime; the
results are the runtime's (`Trajectory`, `Response`, `Cycle`, `Spectrum`, `Sweep`,
`Basins`, `Attractors`, `Coexistence`, `Settled`), their states named by the model.
What a twin cannot honour (a keyword of the paper's integrators, a state the model
lacks) it refuses in one line.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import Unsupported
from ..model import Model
from ..other_model import PAPER
from ..state_names import plane
from .system import System

if TYPE_CHECKING:
    from ..settings import SolverSettings
    from .basins import Basins, Stability
    from .classification import Settled
    from .cycle import Cycle
    from .forced import Response
    from .hybrid import Trajectory
    from .lyapunov import Spectrum
    from .responses import Attractors, Coexistence
    from .sweep import Sweep

__all__ = [
    "system_of", "simulate", "periodic_response", "periodic_start", "cycle", "seed_cycle",
    "lyapunov",
    "sweep", "basins", "basin_stability", "responses", "coexistence", "classify",
]  # fmt: skip


def system_of(model: Model) -> System:
    """The `System` of a `beltmdsm.model.OtherModel` (checked there already)."""
    return System(model.model, model.friction, **model._given)


def _paper_keywords(analysis: str, model: Model, **given: Any) -> None:
    """Refuse a keyword that only the paper's integrators or analyses read."""
    for name, value in given.items():
        if value is not None:
            raise Unsupported(
                f"{analysis}: {name}={value!r} applies to the paper's model, not to "
                f"model {model.model!r} (the generic runtime, beltmdsm/oscillator/)"
            )


def simulate(model: Model, settings: SolverSettings, y0: ArrayLike | None) -> Trajectory:
    """`beltmdsm.simulate` of another model: `beltmdsm.oscillator.simulate`."""
    from .hybrid import simulate as run

    if settings.solver != "events":
        raise Unsupported(
            f"simulate: solver={settings.solver!r} is the paper's; model {model.model!r} "
            "runs on the generic event-driven integrator"
        )
    return run(
        system_of(model), settings.t_end, y0, dt=settings.dt, rtol=settings.rtol,
        atol=settings.atol, backend=settings.backend,
    )  # fmt: skip


def periodic_response(
    model: Model, guess: ArrayLike | None, periods: int, **paper: Any
) -> Response | Cycle:
    """`beltmdsm.floquet` / `periodic_response` of another model: the forced response
    of ``periods`` excitation periods, or without excitation its self-excited cycle
    (both carry their Floquet multipliers)."""
    from .cycles import self_excited_cycle
    from .forced import forced_response

    _paper_keywords("floquet", model, **paper)
    system = system_of(model)
    if system.excitation_period() is None:
        if periods != 1:
            raise ValueError(
                f"periods={periods!r}: model {model.model!r} is unforced here; its "
                "self-excited cycle has no excitation period"
            )
        return self_excited_cycle(system, guess)
    return forced_response(system, guess, periods=periods)


def cycle(model: Model, guess: ArrayLike | None, period: float | None, max_iter: int) -> Cycle:
    """`beltmdsm.cycle` of another model: `beltmdsm.oscillator.self_excited_cycle`."""
    from .cycles import self_excited_cycle

    return self_excited_cycle(system_of(model), guess, period, max_iter=max_iter)


def seed_cycle(
    model: Model, t_end: float | None, perturbation: ArrayLike | None, **paper: Any
) -> tuple[NDArray[np.float64], float]:
    """`beltmdsm.seed_cycle` of another model: `beltmdsm.oscillator.cycle_seed`'s state
    and period, from a run of ``t_end`` seconds (200 by default) off steady sliding moved
    by ``perturbation`` (by default along its least stable direction, then from the stick
    state over it). ``beltmdsm.cycle(model, guess=state, period=period)`` shoots from it."""
    from .cycle_seed import cycle_seed

    _paper_keywords("seed_cycle", model, **paper)
    system = system_of(model)
    if system.excitation_period() is not None:
        raise Unsupported(
            f"seed_cycle: model {model.model!r}: the excitation is on (an amplitude is "
            "not 0): a self-excited cycle needs the autonomous model; beltmdsm.floquet "
            "computes the forced response"
        )
    settle = 200.0 if t_end is None else float(t_end)
    if not (np.isfinite(settle) and settle > 0):
        raise ValueError(f"t_end must be a finite number > 0; got {t_end!r}")
    start = None
    if perturbation is not None:
        m = len(system.states)
        offset = np.asarray(perturbation, dtype=float).ravel()
        if offset.size != m or not np.all(np.isfinite(offset)):
            raise ValueError(
                f"perturbation must be {m} finite numbers ({', '.join(system.states)}); "
                f"got {perturbation!r}"
            )
        from .equilibria import steady_sliding

        start = steady_sliding(system).state + offset
    seed = cycle_seed(system, start, settle=settle)
    return seed.state.copy(), seed.period


def lyapunov(
    model: Model, y0: ArrayLike | None, t_end: float, t_transient: float | None, rtol: float
) -> Spectrum:
    """`beltmdsm.lyapunov` of another model: `beltmdsm.oscillator.lyapunov.lyapunov`."""
    from .lyapunov import lyapunov as spectrum

    return spectrum(system_of(model), y0, t_end=t_end, t_transient=t_transient, rtol=rtol)


def sweep(
    model: Model, param: str, values: ArrayLike, settings: SolverSettings, executor: Any
) -> Sweep:
    """`beltmdsm.sweep` of another model: `beltmdsm.oscillator.sweep.sweep` (an
    executor that is a `concurrent.futures.Executor` runs the points)."""
    from .sweep import sweep as run

    return run(
        system_of(model), param, values, t_end=settings.t_end, t_discard=settings.t_discard,
        dt=settings.dt, rtol=settings.rtol, atol=settings.atol,
        executor=None if executor in (None, "serial") else executor,
    )  # fmt: skip


def basins(
    model: Model,
    x: str,
    x_lo: float | None,
    x_hi: float | None,
    y: str,
    y_lo: float | None,
    y_hi: float | None,
    points: int,
    executor: Any,
    t_end: float,
) -> Basins:
    """`beltmdsm.basins` of another model: `beltmdsm.oscillator.basins.basins`, on the
    plane of two of its states (the paper's default plane read as the model's own,
    `beltmdsm.state_names.plane`)."""
    from .basins import basins as run

    system = system_of(model)
    # the public defaults are the paper's plane: read as this model's own
    default, own = plane(PAPER), plane(model.model)
    x = own[0] if x == default[0] else x
    y = own[1] if y == default[1] else y
    if None in (x_lo, x_hi, y_lo, y_hi):
        raise ValueError(
            f"basins: give x_lo, x_hi, y_lo and y_hi for model {model.model!r} (the ranges "
            "of its states' plane)"
        )
    return run(
        system, x, (x_lo, x_hi), y, (y_lo, y_hi), points=points, t_end=t_end,
        executor=None if executor in (None, "serial") else executor,
    )  # fmt: skip


def periodic_start(model: Model, perturbation: float, **paper: Any) -> NDArray[np.float64]:
    """`beltmdsm.periodic_start` of another model: the state of its periodic orbit
    (`periodic_response`: the forced response at phase 0, or without excitation the
    self-excited cycle's shooting state) with its first state moved by ``perturbation``."""
    _paper_keywords("periodic_start", model, **paper)
    state = periodic_response(model, None, 1).state.copy()
    state[0] += perturbation
    return state


def responses(model: Model, limit: int, t_end: float, **paper: Any) -> Attractors:
    """`beltmdsm.responses` of another model: the stable attractors that runs from a
    grid of starts land on, each shot exactly (`beltmdsm.oscillator.responses`)."""
    from .responses import responses as find

    _paper_keywords("responses", model, **paper)
    return find(system_of(model), t_end=t_end, limit=limit)


def coexistence(
    model: Model, param: str, lo: float, hi: float, points: int, limit: int, **paper: Any
) -> Coexistence:
    """`beltmdsm.coexistence` of another model: `responses` at ``points`` values of
    ``param`` over ``[lo, hi]``, and where two or more stable attractors coexist."""
    from .responses import coexistence as walk

    _paper_keywords("coexistence", model, **paper)
    return walk(system_of(model), param, np.linspace(lo, hi, points), limit=limit)


def classify(
    model: Model, y0: ArrayLike | None, t_end: float, t_transient: float | None, **paper: Any
) -> Settled:
    """`beltmdsm.classify` of another model: `beltmdsm.oscillator.classification.classify`."""
    from .classification import classify as name

    _paper_keywords("classify", model, **paper)
    return name(system_of(model), y0, t_end=t_end, t_transient=t_transient)


def basin_stability(
    model: Model,
    region: Any,
    samples: int,
    seed: int,
    executor: Any,
    t_max: float,
    **paper: Any,
) -> Stability:
    """`beltmdsm.basin.basin_stability.basin_stability` of another model:
    `beltmdsm.oscillator.basins.basin_stability` on the box of two of its states
    (``region``: state -> (low, high), in the plane's order x, y)."""
    from .basins import basin_stability as shares

    _paper_keywords("basin_stability", model, **paper)
    system = system_of(model)
    if not isinstance(region, dict) or len(region) != 2:
        raise ValueError(
            f"region must map two of model {model.model!r}'s states "
            f"({', '.join(system.states)}) to (low, high); got {region!r}"
        )
    (x, x_range), (y, y_range) = region.items()
    return shares(
        system, x, tuple(x_range), y, tuple(y_range), samples=samples, seed=seed,
        t_end=t_max, executor=None if executor in (None, "serial") else executor,
    )  # fmt: skip
