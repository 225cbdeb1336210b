"""The names of a model's states as tables, figures and JSON write them (issue 39).

One source for what a module shared by every model writes of a state: the model's
generated module (``beltmdsm.generated.models.<name>``, read through
`beltmdsm.other_model.model_module`) gives ``STATES`` (the order of ``y``) and
``COORDINATES``. A state among the coordinates is a position; every other state is a
rate, that of the coordinate at its rank among the rates. A state's *column* (a table's
column, a figure's axis label, the prefix of an observable such as ``<column>_amplitude``)
is its own name where the model names its rates ``<q>_dot`` (the models' contract,
``x_dot``), and ``<q>'`` where it names them otherwise: the paper's rates ``Y1`` and
``Y2`` are the columns ``X1'`` and ``X2'``, names its tables and JSON keep (a contract).
A state's unit is its module's ``STATE_UNITS`` (derived from the entry's unit of each
coordinate: ``m`` by default, ``rad`` for an angle, ``1`` for a modal amplitude; a rate in
its coordinate's unit per second); a module typed by hand without it has displacements
(m and m/s), the entries' default. `module_units` reads and checks it.

A model is given as its registered name, a `beltmdsm.model.Model` (its ``model``), an
object holding its generated module as ``module`` (`beltmdsm.oscillator.system.System`,
whose module need not be registered) or naming it as ``name``, the module itself, or
None for the paper's model.
"""

from __future__ import annotations

from types import ModuleType
from typing import Any

from .other_model import PAPER, model_module

__all__ = [
    "names",
    "columns",
    "units",
    "module_units",
    "slip_unit",
    "column",
    "index",
    "rate_column",
    "rate_row",
    "plane",
]

#: The unit of a position and of a rate of a module without ``STATE_UNITS`` (one typed by
#: hand): displacements, the default of a model entry (derive/models/entry.py).
POSITION_UNIT, RATE_UNIT = "m", "m/s"


def _module(model: Any) -> ModuleType:
    if model is None:
        return model_module(PAPER)
    if isinstance(model, str):
        return model_module(model)
    if isinstance(model, ModuleType):
        return model
    module = getattr(model, "module", None)
    if isinstance(module, ModuleType):
        return module
    name = getattr(model, "model", None)
    return model_module(name if isinstance(name, str) else model.name)


def module_units(module: ModuleType) -> tuple[str, ...]:
    """The unit of each state of a model module, in the order of its ``STATES``: its
    ``STATE_UNITS``, checked (one non-empty string per state), or m and m/s where a
    module typed by hand has none.

    Raises
    ------
    ValueError
        Naming the module, where ``STATE_UNITS`` is not one unit string per state.

    See Also
    --------
    units : the same of a model given by name or as a `beltmdsm.model.Model`.

    Examples
    --------
    >>> import types
    >>> toy = types.SimpleNamespace(NAME="toy", COORDINATES=("x",), STATES=("x", "x_dot"))
    >>> module_units(toy)
    ('m', 'm/s')
    >>> toy.STATE_UNITS = ("rad",)
    >>> module_units(toy)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: model 'toy': STATE_UNITS must be one unit string per state ... got ('rad',)
    """
    given = getattr(module, "STATE_UNITS", None)
    if given is None:
        return tuple(POSITION_UNIT if s in module.COORDINATES else RATE_UNIT for s in module.STATES)
    if (
        not isinstance(given, (tuple, list))
        or len(given) != len(module.STATES)
        or not all(isinstance(u, str) and u.strip() for u in given)
    ):
        raise ValueError(
            f"model {module.NAME!r}: STATE_UNITS must be one unit string per state of "
            f"STATES ({', '.join(module.STATES)}); got {given!r}"
        )
    return tuple(given)


def names(model: Any = None) -> tuple[str, ...]:
    """The model's states in the order of ``y`` (its module's ``STATES``).

    Examples
    --------
    >>> names(), names("belt_1dof")
    (('X1', 'Y1', 'X2', 'Y2'), ('x', 'x_dot'))
    """
    return tuple(_module(model).STATES)


def _rates(module: ModuleType) -> dict[str, str]:
    """Each rate's state name -> its coordinate."""
    rates = [s for s in module.STATES if s not in module.COORDINATES]
    return dict(zip(rates, module.COORDINATES))


def columns(model: Any = None) -> tuple[str, ...]:
    """The model's states as a table's columns and a figure's labels, in the order of ``y``.

    Parameters
    ----------
    model : str, beltmdsm.model.Model or None
        the model (None: the paper's)

    Returns
    -------
    tuple of str

    See Also
    --------
    names : the states as the model names them.

    Examples
    --------
    >>> columns(), columns("belt_1dof"), columns("hoffmann")
    (('X1', "X1'", 'X2', "X2'"), ('x', 'x_dot'), ('x', 'y', 'x_dot', 'y_dot'))
    """
    module = _module(model)
    rates = _rates(module)
    return tuple(
        s if s not in rates or s == f"{rates[s]}_dot" else f"{rates[s]}'" for s in module.STATES
    )


def units(model: Any = None) -> tuple[str, ...]:
    """The unit of each state, in the order of ``y`` (`module_units`: the model's
    ``STATE_UNITS``).

    Examples
    --------
    >>> units(), units("belt_1dof")
    (('m', 'm/s', 'm', 'm/s'), ('m', 'm/s'))
    """
    return module_units(_module(model))


def slip_unit(model: Any = None) -> str:
    """The unit of the slip velocity ``v_r = w . q' - Vb``: the belt speed's (the module's
    ``UNITS["Vb"]``), whatever the units of the coordinates (a rotational coordinate
    enters ``v_r`` through its lever arm).

    Examples
    --------
    >>> slip_unit("hoffmann")
    'm/s'
    """
    return _module(model).UNITS["Vb"]


def index(model: Any, name: str) -> int:
    """The position in ``y`` of the state ``name`` (its name or its column).

    Raises
    ------
    ValueError
        Naming the model's states, for another name.

    Examples
    --------
    >>> index(None, "Y1"), index(None, "X1'"), index("hoffmann", "y_dot")
    (1, 1, 3)
    """
    module = _module(model)
    for table in (tuple(module.STATES), columns(model)):
        if name in table:
            return table.index(name)
    raise ValueError(
        f"not a state of model {module.NAME!r} ({', '.join(module.STATES)}); got {name!r}"
    )


def column(model: Any, name: str) -> str:
    """The column of the state ``name`` (its name or its column).

    Examples
    --------
    >>> column(None, "Y2"), column("belt_1dof", "x_dot")
    ("X2'", 'x_dot')
    """
    return columns(model)[index(model, name)]


def rate_column(model: Any = None, coordinate: int = 0) -> str:
    """The column of the rate of the model's ``coordinate``-th coordinate (the default
    observable of a branch, ``<rate>_amplitude``).

    Examples
    --------
    >>> rate_column(), rate_column("belt_1dof"), rate_column("hoffmann", 1)
    ("X1'", 'x_dot', 'y_dot')
    """
    module = _module(model)
    rate = next(s for s, q in _rates(module).items() if q == module.COORDINATES[coordinate])
    return column(model, rate)


def plane(model: Any = None) -> tuple[str, str]:
    """The states of the model's first coordinate and of its rate, as the model names
    them: the default plane of a basin map.

    Examples
    --------
    >>> plane(), plane("belt_1dof")
    (('X1', 'Y1'), ('x', 'x_dot'))
    """
    module = _module(model)
    rate = next(s for s, q in _rates(module).items() if q == module.COORDINATES[0])
    return module.COORDINATES[0], rate


def rate_row(model: Any = None, coordinate: int = 0) -> int:
    """The row of ``y`` of the rate of the model's ``coordinate``-th coordinate.

    Examples
    --------
    >>> rate_row(), rate_row("hoffmann"), rate_row("hoffmann", 1)
    (1, 2, 3)
    """
    return index(model, rate_column(model, coordinate))
