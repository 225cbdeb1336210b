"""Units of the contact law's stiffness and damping, derived from its force.

``omega2`` and ``beta2`` mean different things under different contact laws: Eq. (1)
makes ``omega2*`` a stiffness in rad/(m^(1/4) s) and ``beta2*`` a damping in
1/m^(5/4), the linear law of Fig. 16 an ordinary frequency and damping ratio, and the
Hunt-Crossley law units that depend on its exponent. Each follows from one
requirement: every term of the force per unit mass is an acceleration (m/s^2).
`contact_units` solves the exponents of metre and second of each parameter with
`beltmdsm.derive.parameters.Parameter.derived_unit` from that requirement (SymPy), so no unit
string is typed per law.
"""

from __future__ import annotations

from functools import cache

import sympy as sp

from . import laws
from .model import X2, Y2, P

__all__ = ["METRE", "SECOND", "contact_units", "format_unit"]

METRE, SECOND = sp.symbols("m s", positive=True)


def _exponents(monomial: sp.Expr) -> tuple[sp.Expr, sp.Expr]:
    """Exponents of metre and second in a product of powers of them (numbers ignored)."""
    logged = sp.expand_log(sp.log(monomial), force=True)
    return logged.coeff(sp.log(METRE)), logged.coeff(sp.log(SECOND))


def format_unit(m: sp.Expr, s: sp.Expr, radian: bool = False) -> str:
    """``m^a s^b`` as the parameter table writes units: ``rad/(m^(1/4) s)``, ``1/m^(5/4)``.

    A factor goes below the fraction bar when SymPy proves its exponent negative,
    above it otherwise (an exponent of unknown sign, such as ``(1 - n_h)/2``).
    """
    above, below = (["rad"] if radian else []), []
    for name, e in (("m", sp.sympify(m)), ("s", sp.sympify(s))):
        if e == 0:
            continue
        side, e = (below, sp.together(-e)) if e.is_negative else (above, sp.together(e))
        text = sp.sstr(e)
        side.append(name if e == 1 else f"{name}^{text if e.is_Integer else f'({text})'}")
    top = " ".join(above) or "1"
    if not below:
        return top
    bottom = below[0] if len(below) == 1 else f"({' '.join(below)})"
    return f"{top}/{bottom}"


@cache
def contact_units(contact: str) -> dict[str, str]:
    """The unit of each parameter with a derived unit under the contact law ``contact``.

    Raises
    ------
    ValueError
        If a parameter of the force has a unit other than ``1`` and is not derived,
        or if the terms of the force do not fix the exponents.
    """
    force = sp.expand(laws.get("contact", contact).force(P, X2, Y2))
    table = {p.name: p for p in laws.parameter_table()}
    unknown, dims = {}, {X2: METRE, Y2: METRE / SECOND}
    for sym in sorted(force.free_symbols - {X2, Y2}, key=lambda x: x.name):
        p = table[sym.name]
        if p.derived_unit:
            unknown[sym.name] = sp.symbols(f"m_{sym.name} s_{sym.name}", real=True)
            dims[sym] = METRE ** unknown[sym.name][0] * SECOND ** unknown[sym.name][1]
        elif p.unit != "1":
            raise ValueError(f"{contact}: cannot derive units with {sym.name} in {p.unit}")
        # a dimensionless parameter (an exponent) is left in place
    equations = []
    for term in sp.Add.make_args(force):
        m, s = _exponents(sp.powsimp(term.xreplace(dims), force=True))
        equations += [m - 1, s + 2]  # an acceleration, m/s^2
    solution = sp.solve(equations, [x for pair in unknown.values() for x in pair], dict=True)
    if len(solution) != 1:
        raise ValueError(f"{contact}: the force does not fix the units of {sorted(unknown)}")
    out = {}
    for name, (m, s) in unknown.items():
        m, s = solution[0].get(m, m), solution[0].get(s, s)
        if (m.free_symbols | s.free_symbols) & {x for pair in unknown.values() for x in pair}:
            raise ValueError(f"{contact}: the force does not fix the unit of {name}")
        out[name] = format_unit(m, s, radian=table[name].unit.startswith("rad"))
    return out
