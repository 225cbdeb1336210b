"""The period maps by engine, and the choice between them by the facts of the model's laws.

`period_map` is the ``k``-fold period map of a model (`beltmdsm.periodic.base.PeriodMap`):
the closed-form one (`beltmdsm.periodic.closed_form.ClosedFormMap`) where the model's laws
have every fact of `CLOSED_FORM_FACTS` (``beltmdsm.generated.capabilities``, decided by SymPy),
else the general one (`beltmdsm.periodic.general_map.GeneralMap`), or the one asked for.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

from ..model import Backend, Model
from ..settings import check_finite
from .base import Engine, PeriodMap
from .closed_form import CLOSED_FORM_FACTS, ClosedFormMap
from .general_map import GeneralMap

__all__ = [
    "ENGINES",
    "engine_of",
    "period_map",
]

#: The period maps by engine name.
ENGINES: dict[str, type[PeriodMap]] = {"closed_form": ClosedFormMap, "general": GeneralMap}


def engine_of(model: Model) -> str:
    """The engine of the model's laws: ``"closed_form"`` where they have every fact of
    `CLOSED_FORM_FACTS`, else ``"general"``.

    Parameters
    ----------
    model : Model

    Returns
    -------
    {"closed_form", "general"}

    Raises
    ------
    KeyError
        For laws that ``beltmdsm.generated.capabilities`` does not know (a model checks its
        options, so not for a `beltmdsm.model.Model`).

    See Also
    --------
    period_map : the map of that engine.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> engine_of(Model()), engine_of(Model(friction="stribeck"))
    ('closed_form', 'general')
    """
    return "closed_form" if all(model.fact(f)[0] for f in CLOSED_FORM_FACTS) else "general"


def period_map(
    model: Model,
    periods: int = 1,
    backend: Backend | None = None,
    engine: Engine | None = None,
    *,
    check: bool = True,
) -> PeriodMap:
    """The ``k``-fold period map of the model.

    Parameters
    ----------
    model : Model
    periods : int
    backend : {"python", "numba", None}
    engine : {"closed_form", "general", None}
        None: the engine the model's laws allow (`engine_of`); a name asks for that
        engine (the general one applies to every law, and serves as a cross-check of
        the closed-form one).
    check : bool
        Refuse a start beyond floating point (`beltmdsm.settings.check_finite`, 0.3 ms
        the first time, its verdict then kept per model); False where the caller
        checked the model where it entered: `beltmdsm.periodic.family.MapFamily` checks
        its model once instead of at every value (an overflow there still ends its
        runs, with `beltmdsm.errors.StepTooSmall`).

    Raises
    ------
    ValueError
        For an unknown engine; `beltmdsm.errors.Refused` for parameters that put the
        start beyond floating point (`beltmdsm.settings.check_finite`).
    beltmdsm.model.Unsupported
        For ``engine="closed_form"`` where the laws lack a fact it needs.

    See Also
    --------
    beltmdsm.periodic.base.PeriodMap : what it returns.
    beltmdsm.periodic.newton.fixed_point : the shooting on it.
    beltmdsm.periodic.family.MapFamily : the maps of one parameter's values.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> type(period_map(Model(Vb=5.0))).__name__, period_map(Model(Vb=5.0), 4).periods
    ('ClosedFormMap', 4)
    >>> period_map(Model(Vb=5.0), engine="general").dimension  # the full state
    4
    >>> period_map(Model(), engine="fast")
    Traceback (most recent call last):
    ...
    ValueError: engine must be one of 'closed_form', 'general'; got 'fast'
    """
    if engine is not None and engine not in ENGINES:
        raise ValueError(f"engine must be one of {', '.join(map(repr, ENGINES))}; got {engine!r}")
    if check:
        check_finite(model)
    return ENGINES[engine or engine_of(model)](model, periods, backend)
