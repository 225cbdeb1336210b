"""The units of a model's coordinates: each rate's unit, and the slip form's dimension.

A coordinate has a unit of its own (``Oscillator.units``; a length in ``m`` unless the
entry says otherwise: an angle in ``rad``, a modal amplitude in ``1`` or any unit
string), and its rate the coordinate's unit per second (`rate_unit`). The slip velocity
``v_r = w . q' - Vb`` is the contact's, in the unit of ``Vb``: a rotational coordinate
enters it through its lever arm, ``v_r = r theta' - Vb`` with ``r`` in m. `slip_mismatch`
checks that cheaply: each coefficient's unit (its parameters' units multiplied out)
times its rate's unit must be the unit of ``Vb``, ``rad`` counting as 1 (an angle is a
ratio of lengths). It reads the units written with the words of `VOCABULARY` (products
by a space, quotients by ``/``, powers by ``^``, parentheses); a coefficient or a
coordinate in any other unit is not checked (the check says nothing of it, it does not
pass it). The friction direction, the matrices and the forces are not checked: their
units depend on how the entry scales its equations (per unit mass, per unit inertia).
"""

from __future__ import annotations

import re

import sympy as sp

__all__ = ["LENGTH", "VOCABULARY", "rate_unit", "parse", "slip_mismatch"]

#: A coordinate's unit where the entry names none.
LENGTH = "m"

_KG, _M, _S = sp.symbols("kg m s", positive=True)
#: The unit words the slip form's check reads, in SI base units (``rad`` as 1).
VOCABULARY = {"m": _M, "s": _S, "kg": _KG, "N": _KG * _M / _S**2, "rad": sp.Integer(1)}
_WORD = re.compile(r"[A-Za-z_]\w*")
_ALLOWED = re.compile(r"^[\w\s()/^.*-]*$")


def rate_unit(unit: str) -> str:
    """The unit of a coordinate's rate: the coordinate's per second.

    Examples
    --------
    >>> rate_unit("m"), rate_unit("rad"), rate_unit("1"), rate_unit("m/rad")
    ('m/s', 'rad/s', '1/s', '(m/rad)/s')
    """
    if "/" in unit or " " in unit.strip():
        return f"({unit})/s"
    return f"{unit}/s"


def parse(unit: str) -> sp.Expr | None:
    """The unit in SI base units, or None where it uses a word outside `VOCABULARY`.

    Examples
    --------
    >>> parse("N s/m"), parse("1/(m^2 s^2)"), parse("rad/s"), parse("deg") is None
    (kg/s, 1/(m**2*s**2), 1/s, True)
    """
    text = unit.strip()
    if not text or not _ALLOWED.match(text) or set(_WORD.findall(text)) - set(VOCABULARY):
        return None
    text = re.sub(r"(?<=[\w)])\s+(?=[\w(])", "*", text.replace("^", "**"))
    try:
        value = sp.sympify(text, locals=dict(VOCABULARY))
    except (sp.SympifyError, SyntaxError, TypeError):
        return None
    return value if isinstance(value, sp.Expr) and value.free_symbols <= {_KG, _M, _S} else None


def _unit_of(expr: sp.Expr, units: dict[sp.Symbol, sp.Expr | None]) -> sp.Expr | None:
    """The unit of an expression of parameters: a product of powers of them (numbers
    dimensionless); None where a parameter's unit is unread or the terms of a sum
    differ."""
    expr = sp.sympify(expr)
    if expr.is_Number:
        return sp.Integer(1)
    if expr.is_Symbol:
        return units.get(expr)
    if expr.is_Add:
        found = {_unit_of(a, units) for a in expr.args}
        return found.pop() if len(found) == 1 else None
    if expr.is_Mul:
        out = sp.Integer(1)
        for a in expr.args:
            u = _unit_of(a, units)
            if u is None:
                return None
            out *= u
        return out
    if expr.is_Pow and expr.exp.is_Number:
        base = _unit_of(expr.base, units)
        return None if base is None else base**expr.exp
    return None


def slip_mismatch(coefficients, coordinate_units, parameter_units, vb_unit) -> str | None:
    """What is wrong with the slip form's units, or None (module docstring).

    Parameters
    ----------
    coefficients : dict
        Coordinate name -> its coefficient ``w_i`` (a SymPy expression of parameters).
    coordinate_units : dict
        Coordinate name -> its unit.
    parameter_units : dict
        Parameter symbol -> its unit string.
    vb_unit : str
        The unit of ``Vb`` (that of ``v_r``).

    Examples
    --------
    >>> r = sp.Symbol("r")
    >>> slip_mismatch({"theta": r}, {"theta": "rad"}, {r: "m"}, "m/s") is None
    True
    >>> print(slip_mismatch({"theta": 1}, {"theta": "rad"}, {}, "m/s"))  # doctest: +ELLIPSIS
    the term of theta' is in 1/s (its coefficient in 1, theta in rad, ...), not in m/s, ...
    """
    target = parse(vb_unit)
    if target is None:
        return None
    units = {p: parse(u) for p, u in parameter_units.items()}
    for name, w in coefficients.items():
        w = sp.sympify(w)
        if w == 0:
            continue
        u_w, u_q = _unit_of(w, units), parse(coordinate_units[name])
        if u_w is None or u_q is None:
            continue
        term = sp.simplify(u_w * u_q / _S)
        if sp.simplify(term / target) != 1:
            return (
                f"the term of {name}' is in {sp.sstr(term)} (its coefficient in "
                f"{sp.sstr(u_w)}, {name} in {coordinate_units[name]}, rad counted as 1), not "
                f"in {vb_unit}, the unit of Vb: a rotational coordinate enters through its "
                f"lever arm (v_r = r {name}' - Vb, r in m)"
            )
    return None
