"""A study written against the public API, type-checked (never run) by
tests/beltmdsm/test_public_types.py: mypy, with ``--disallow-any-expr``, must find no
expression of type ``Any`` here, and each ``reveal_type`` must name the real type
(``reveal_type`` is the type checker's own)."""

# ruff: noqa: F821

import beltmdsm
from beltmdsm import (
    BeltmdsmError,
    Model,
    NoPeriodicResponse,
    Refused,
    StepTooSmall,
    Unsupported,
    basins,
    branch,
    classify,
    coexistence,
    cycle,
    floquet,
    floquet_band,
    floquet_map,
    lyapunov,
    simulate,
    sweep,
)

model = Model(Vb=5.0)
reveal_type(model)
run = simulate(model, t_end=50.0)
reveal_type(run)
reveal_type(run.summary)
growth: float = floquet(model).growth_rate
reveal_type(floquet(model))
reveal_type(floquet_band(model, "Vb", 1.0, 8.0))
reveal_type(floquet_band("Vb", 1.0, 8.0, model))
reveal_type(branch(model, param="Vb", lo=1.0, hi=8.0))
reveal_type(coexistence(model, "Vb", 1.0, 8.0))
reveal_type(sweep(model, "Vb", [1.0, 2.0], t_end=50.0))
reveal_type(floquet_map(model, "Vb", 1.0, 8.0, "beta1", 0.05, 0.35))
reveal_type(cycle(Model(friction="stribeck", alpha=0.0, Vb=1.5)))
reveal_type(lyapunov(model, t_end=300.0))
largest: float = lyapunov(model, t_end=300.0).largest
reveal_type(classify(model))
reveal_type(basins(model, points=3))
# issue 37: a cycle branch's Hopf point; lyapunov takes a dict as at run time
hopf = branch(Model(friction="stribeck", alpha=0.0), lo=1.9, hi=2.1).hopf
born: float = hopf.value if hopf is not None else 0.0
params: dict[str, float] = {"Vb": 5.0}
reveal_type(lyapunov(params, y0=[0.0, 0.0, 1.0, 0.0], t_end=300, t_transient=0))
reveal_type(floquet_band(model, "Vb", 1.0, 8.0, points=5))
version: str = beltmdsm.__version__
failures: tuple[type[BeltmdsmError], ...] = (Refused, Unsupported, StepTooSmall, NoPeriodicResponse)
