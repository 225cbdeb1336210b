"""The words of the figures (`beltmdsm.plotting`): each state's, parameter's and
observable's axis label with its unit, and a response's name.

A state is named as the model's tables name it (`beltmdsm.state_names`), a parameter's
unit is the parameter table's (``beltmdsm.generated.parameters``) or the one its contact
law gives (``LAW_UNITS``). No matplotlib here: the labels are text.
"""

from __future__ import annotations

from typing import Any

from beltmdsm.generated.parameters import LAW_UNITS, PARAMETERS

from . import state_names

__all__ = ["STATE", "axis_label", "observable_label", "response_name", "unit"]


def _model_of(result: Any) -> Any:
    """The model a result was computed for: its ``model`` (a `beltmdsm.model.Model`), or
    the ``system`` of a run of the generic runtime (`beltmdsm.oscillator.system.System`)."""
    return result.model if hasattr(result, "model") else result.system


def _state_rows(model: Any) -> dict[str, tuple[str, int]]:
    """``{column: (unit, row of y)}`` of the model's states (`beltmdsm.state_names`)."""
    return {
        c: (u, i)
        for i, (c, u) in enumerate(zip(state_names.columns(model), state_names.units(model)))
    }


#: The rows of a run of the paper's model and their units (another model's:
#: `beltmdsm.state_names`).
STATE = _state_rows(None)
_UNITS = {p["name"]: p["unit"] for p in PARAMETERS}


def unit(name: str, model: Any = None) -> str:
    """The unit of parameter ``name`` (under the model's contact law, where it has one).

    Parameters
    ----------
    name : str
        a parameter of the model (``beltmdsm.generated.parameters``)
    model : beltmdsm.model.Model, optional
        whose contact law may give the parameter another unit

    Returns
    -------
    str

    Raises
    ------
    KeyError
        if ``name`` is not a parameter.

    See Also
    --------
    beltmdsm.plotting.axis_label

    Examples
    --------
    The contact stiffness ``beta2`` is dimensionless in the Kelvin-Voigt law, not in
    the Hertz law of the default model:

    >>> from beltmdsm import Model
    >>> unit("Vb"), unit("beta2"), unit("beta2", Model(contact="kelvin_voigt"))
    ('m/s', '1/m^(5/4)', '1')
    """
    if model is not None:
        for (option, choice), units in LAW_UNITS.items():
            if getattr(model, option, None) == choice and name in units:
                return units[name]
    return _UNITS[name]


def axis_label(name: str, unit_: str) -> str:
    """``"Vb [m/s]"``; a dimensionless quantity ``"[-]"``.

    Parameters
    ----------
    name : str
        the quantity
    unit_ : str
        its unit; ``"1"`` for a dimensionless one

    Returns
    -------
    str

    See Also
    --------
    beltmdsm.plotting.unit

    Examples
    --------
    >>> axis_label("Vb", "m/s"), axis_label("beta1", "1")
    ('Vb [m/s]', 'beta1 [-]')
    """
    return f"{name} [{'-' if unit_ == '1' else unit_}]"


def response_name(periods: int) -> str:
    """``"T"`` or ``"4T"``: a response of ``periods`` excitation periods."""
    return "T" if periods == 1 else f"{periods}T"


def observable_label(name: str, model: Any = None) -> str:
    """The axis label of an observable of `beltmdsm.periodic.observables` or of another
    model's branch (``<state>_amplitude``, ``_min``, ``_max`` of a state of the model,
    `beltmdsm.state_names.columns`, in the state's unit, `beltmdsm.state_names.units`: m
    and m/s for a displacement and its rate, rad and rad/s for an angle; the paper's m/s
    for Vr, m/s^2 for a force per unit mass); a column of a user's ``record`` is
    labelled by its name.

    Parameters
    ----------
    name : str
        a column of a branch's observables
    model : str, beltmdsm.model.Model or beltmdsm.oscillator.System, optional
        the branch's model (None: the paper's)

    Returns
    -------
    str

    See Also
    --------
    beltmdsm.plotting.branch

    Examples
    --------
    >>> observable_label("X1'_amplitude"), observable_label("mu_eff")
    ("X1' amplitude [m/s]", 'mu_eff = <Ff>/<Fn> [-]')
    >>> observable_label("energy")
    'energy (recorded)'
    >>> observable_label("x_dot_amplitude", "belt_1dof")
    'x_dot amplitude [m/s]'
    >>> observable_label("max_abs_v_r", "hoffmann")
    'max |v_r| [m/s]'
    """
    for column, (unit_, _) in _state_rows(model).items():
        head, _, tail = name.rpartition("_")
        if head == column and tail in ("amplitude", "min", "max"):
            return axis_label(f"{column} {tail}", unit_)
    if name in ("v_r_min", "v_r_max"):  # another model's orbit (beltmdsm/oscillator/orbit.py)
        return axis_label(f"v_r {name.removeprefix('v_r_')}", state_names.slip_unit(model))
    if name == "max_abs_v_r":
        return axis_label("max |v_r|", state_names.slip_unit(model))
    if name == "max_abs_Vr":
        return axis_label("max |Vr|", "m/s")
    if name == "mean_friction":
        return axis_label("mean friction per unit mass", "m/s^2")
    if name == "mu_eff":
        return axis_label("mu_eff = <Ff>/<Fn>", "1")
    return f"{name} (recorded)"
