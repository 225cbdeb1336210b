"""The registry of models, beside the registry of laws: ``register("model", entry)``.

`register` takes every option of `beltmdsm.derive.laws.register` (``"friction"``,
``"contact"``, ``"tension"``: handed on to it) and ``"model"``, an `Oscillator`
entry. A model entry is checked where it enters (`check`): what the derivation
cannot take is refused in one line naming the model and what is wrong. The first
registered model, ``paper``, is the default.
"""

from __future__ import annotations

import keyword

import sympy as sp

from .. import laws
from ..model import t
from .dimensions import slip_mismatch
from .entry import NORMAL, Oscillator
from .system import law_parameters, model_parameters, system

__all__ = [
    "MODELS", "register", "choices", "default", "get", "check", "RESERVED", "UnsupportedModel",
]  # fmt: skip


class UnsupportedModel(ValueError):
    """A model entry `register` refuses: one line naming the model and what is wrong
    (``python -m derive`` prints it as one line, exit status 2)."""


#: model name -> entry, in registration order (the default first).
MODELS: dict[str, Oscillator] = {}
#: Names the generated modules use themselves: no coordinate or parameter may take one.
RESERVED = frozenset({"t", "state", "params", "mode", "math", "numpy", "NamedTuple", "lambda_h"})


def register(option: str, entry):
    """Add ``entry`` to the registry of ``option``: a model (``"model"``) or a law.

    Parameters
    ----------
    option : str
        ``"model"``, or an option of `beltmdsm.derive.laws.OPTIONS` (handed on to
        `beltmdsm.derive.laws.register`).
    entry : Oscillator or Law

    Returns
    -------
    The entry as registered.

    Raises
    ------
    UnsupportedModel
        A ValueError: one line naming the model and what is wrong (`check`), or a name
        taken.

    See Also
    --------
    beltmdsm.derive.laws.register : the laws' registry.

    Examples
    --------
    >>> from beltmdsm.derive.models import get
    >>> get("belt_1dof").coordinates
    ('x',)
    """
    if option != "model":
        return laws.register(option, entry)
    if not isinstance(entry, Oscillator):
        raise UnsupportedModel(f"a model must be an Oscillator; got {type(entry).__name__}")
    if entry.name in MODELS:
        raise UnsupportedModel(f"model {entry.name!r} is registered already")
    check(entry)
    MODELS[entry.name] = entry
    return entry


def choices() -> tuple[str, ...]:
    """The registered models, the default (``paper``) first."""
    return tuple(MODELS)


def default() -> str:
    """The default model: the first registered, ``paper``."""
    return choices()[0]


def get(name: str) -> Oscillator:
    """The model ``name``.

    Raises
    ------
    ValueError
        Naming the registered models, for an unknown name.
    """
    try:
        return MODELS[name]
    except KeyError:
        raise ValueError(f"model must be one of {choices()}; got {name!r}") from None


def _refuse(entry, what):
    raise UnsupportedModel(f"model {entry.name!r}: {what}")


def _names(entry):
    if not entry.name.isidentifier() or keyword.iskeyword(entry.name):
        _refuse(
            entry, "its name must be a Python identifier (the module generated/models/<name>.py)"
        )
    n = len(entry.coordinates)
    if n < 1:
        _refuse(entry, "coordinates: at least one generalized coordinate")
    states = (*entry.coordinates, *entry.rate_names)
    params = [p.name for p in entry.parameters]
    for kind, names in (("coordinates and rates", states), ("parameters", params)):
        for name in names:
            if not name.isidentifier() or name.startswith("_") or name in RESERVED:
                _refuse(
                    entry,
                    f"{kind}: {name!r} is not a free identifier (reserved: "
                    f"{', '.join(sorted(RESERVED))}; no leading underscore)",
                )
        if len(set(names)) != len(names):
            _refuse(entry, f"{kind}: a name is listed twice ({names})")
    if len(entry.rate_names) != n:
        _refuse(entry, f"rates: {len(entry.rate_names)} names for {n} coordinates")
    if set(states) & set(params):
        _refuse(
            entry, f"a name is both a state and a parameter: {sorted(set(states) & set(params))}"
        )
    if sorted(entry.state_names) != sorted(states):
        _refuse(entry, f"states: {entry.state_names} must order exactly {states}")
    if "Vb" not in params:
        _refuse(entry, "parameters: the belt speed Vb is missing (v_r = w . q' - Vb)")
    _units(entry)


def _units(entry):
    units = entry.units or {}
    if not hasattr(units, "items"):
        _refuse(entry, f"units: a mapping of coordinate -> unit; got {type(units).__name__}")
    for name, unit in units.items():
        if name not in entry.coordinates:
            _refuse(entry, f"units: {name!r} is not a coordinate {entry.coordinates}")
        if not isinstance(unit, str) or not unit.strip() or not unit.isprintable():
            _refuse(entry, f"units: {name!r} needs a one-line unit string; got {unit!r}")


def _laws(entry):
    for law in entry.friction_laws or ():
        if law not in laws.choices("friction"):
            _refuse(
                entry,
                f"friction_laws: {law!r} is not a registered friction law "
                f"{laws.choices('friction')}",
            )
    c = entry.contact
    if c.unilateral:
        if c.normal not in entry.coordinates:
            _refuse(entry, f"contact.normal: {c.normal!r} is not a coordinate {entry.coordinates}")
        if c.law not in laws.choices("contact"):
            _refuse(
                entry,
                f"contact.law: {c.law!r} is not a registered contact law {laws.choices('contact')}",
            )
    for x in entry.excitation:
        if x.target not in entry.coordinates and not (x.target == NORMAL and not c.unilateral):
            _refuse(
                entry,
                f"excitation: target {x.target!r} is neither a coordinate nor "
                "'normal' (a bilateral contact's load)",
            )
        for name in (x.amplitude, x.frequency, x.phase):
            if name not in {p.name for p in entry.parameters}:
                _refuse(entry, f"excitation: {name!r} is not one of the model's parameters")
        if x.sign not in (1, -1):
            _refuse(entry, f"excitation: sign must be 1 or -1; got {x.sign!r}")


def _expressions(entry):
    """The derived equations: only known symbols, a nonsingular mass matrix, a slip form
    free of the state, a friction direction along which the slip velocity moves."""
    friction = (entry.friction_laws or laws.choices("friction"))[0]
    try:
        sys_ = system(entry, friction)
    except KeyError as err:
        _refuse(entry, f"{err.args[0]!r} is neither a parameter nor a coordinate of it")
    except (TypeError, ValueError, sp.SympifyError, sp.ShapeError) as err:
        _refuse(entry, f"its equations do not derive: {err}")
    known = set(sys_.state) | set(sys_.params) | {t}
    for f in sys_.fields.values():
        stray = {s.name for s in f.free_symbols - known}
        if stray:
            _refuse(entry, f"symbols that are neither states nor parameters: {sorted(stray)}")
    if set(sys_.state) & sp.Matrix([sys_.slip]).free_symbols - set(sys_.v):
        _refuse(entry, "contact.slip: the slip form's coefficients depend on the coordinates")
    if all(sp.diff(sys_.slip, v) == 0 for v in sys_.v):
        _refuse(entry, "contact.slip: all coefficients are zero (no slip velocity)")
    rows = model_parameters(entry) + law_parameters(entry, friction)
    wrong = slip_mismatch(
        {q.name: sp.diff(sys_.slip, v) for q, v in zip(sys_.q, sys_.v)},
        dict(zip(entry.coordinates, entry.coordinate_units)),
        {sys_.P[r.name]: r.unit for r in rows},
        next(r.unit for r in rows if r.name == "Vb"),
    )
    if wrong:
        _refuse(entry, f"contact.slip: {wrong}")


def check(entry: Oscillator) -> None:
    """Refuse, in one line naming what is wrong, an entry the derivation cannot take."""
    _names(entry)
    _laws(entry)
    _expressions(entry)
