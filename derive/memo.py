"""SymPy's `simplify` and `factor`, computed once per expression in a derivation.

SymPy's cache keeps the construction of expressions and a few helpers, not `simplify`
or `factor`. The derivation meets the same expression in several places (the normal
block of every friction law's Jacobian, the entries each convention's forced Jacobian
shares, the law's remainder tested for zero by each average) and simplified it again
each time: 290 of 367 calls were repeats. SymPy expressions are immutable and these
functions deterministic, so a result is kept and handed out again (the same object).
"""

from __future__ import annotations

from functools import cache

import sympy as sp

__all__ = ["simplify", "factor"]


@cache
def simplify(expr: sp.Basic) -> sp.Basic:
    """``sympy.simplify(expr)``, once per expression."""
    return sp.simplify(expr)


@cache
def factor(expr: sp.Basic) -> sp.Basic:
    """``sympy.factor(expr)``, once per expression."""
    return sp.factor(expr)
