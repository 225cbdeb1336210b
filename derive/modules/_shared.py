"""What the spec modules share: the law options of the registry, one variant per
choice of laws, refusals, and the docs of the state arguments."""

from __future__ import annotations

import itertools

from .. import budget, laws
from ..codegen import NoVariant

_WHAT = {
    "friction": "friction law (derive/laws.py)",
    "contact": "contact law (derive/laws.py)",
    "tension": "tension law (derive/laws.py; docs/modelling.md#tension)",
}


def law_options(*options: str) -> tuple:
    """The ``(name, choices, default, description)`` rows of the law options, from the registry."""
    rows = []
    for option in options:
        choices = laws.choices(option)
        doc = "; ".join(f"{c}: {laws.get(option, c).summary}" for c in choices)
        rows.append(
            (
                option,
                "{" + ", ".join(f'"{c}"' for c in choices) + "}",
                laws.default(option),
                f"{_WHAT[option]}: {doc}.",
            )
        )
    return tuple(rows)


def _or_refuse(expr, reason: str):
    """``expr``, or a `NoVariant` with ``reason`` where the derivation claims no closed form
    (with the budget's reason where a step ran past its budget, `beltmdsm.derive.budget`)."""
    if isinstance(expr, budget.NoClosedForm):
        return NoVariant(
            f"{reason.split(':')[0]}: {expr.reason}; no closed-form boundary is claimed"
        )
    return NoVariant(reason) if expr is None else expr


def _per(build, *options: str) -> dict:
    """``{(choice, ...): build(choice, ...)}`` over every combination of the options' choices."""
    keys = itertools.product(*(laws.choices(o) for o in options))
    return {key: build(*key) for key in keys}


FRICTION = law_options("friction")
CONTACT = law_options("contact")
LAWS_FC = law_options("friction", "contact")
CONTACT_TENSION = law_options("contact", "tension")
LAWS_FCT = law_options("friction", "contact", "tension")
STATE_DOCS = {
    "X1": "tangential displacement [m]",
    "Y1": "tangential velocity X1' [m/s]",
    "X2": "normal penetration into the belt [m]",
    "Y2": "normal velocity X2' [m/s]",
    "t": "time [s]",
    "sgn": "friction direction: -1 (mass slower than the belt), +1, "
    "or 0 (no friction: the force sticking must supply)",
}
IN_CONTACT = {"X2": ("positive", "Eqs. (5)-(8) hold in contact only, X2 > 0")}
