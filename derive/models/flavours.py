"""The two flavours of a model module's text: numpy (generated/models/) and mpmath
(generated/mp/models/, its twin at ``mpmath.mp.dps`` digits).

One generator (`beltmdsm.derive.models.render`) walks the same SymPy expressions, after
the same common-subexpression elimination, for both; a flavour says only how a number,
an input, a vector and a matrix are written and which printer prints the expressions
(PyDy's generator / printer split). The mpmath twin converts every input to ``mpf`` where
it is read (a float times a float would otherwise round to double before it meets an
``mpf``), returns lists for vectors and ``mpmath.matrix`` for matrices, as the paper's
twins in generated/mp/ do.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from ..codegen.printers import Mpmath, Scalar
from ..model import t

__all__ = ["Flavour", "NUMPY", "MPMATH"]


@dataclass(frozen=True)
class Flavour:
    """How one flavour writes a kernel's pieces (module docstring)."""

    mp: bool
    printer: object

    def number(self, e) -> str:
        """A constant output (a whole entry that is a number)."""
        if not e.is_Number:
            return self.printer.doprint(e)
        if not self.mp:
            return repr(float(e))
        return f"mpmath.mpf({int(e)})" if e.is_Integer else self.printer.doprint(e)

    def read(self, source: str) -> str:
        """An input read from ``state[i]``, ``params[i]``, ``q[i]``, ``a[i]`` or ``t``."""
        return f"mpmath.mpf({source})" if self.mp else source

    def vector(self, items) -> str:
        if self.mp:
            return f"return [{', '.join(items)}]"
        return f"return numpy.array(({', '.join(items)},), dtype=numpy.float64)"

    def matrix(self, rows) -> str:
        if self.mp:
            return f"return mpmath.matrix([{', '.join('[' + ', '.join(r) + ']' for r in rows)}])"
        inner = ", ".join(f"({', '.join(r)},)" for r in rows)
        return f"return numpy.array(({inner},), dtype=numpy.float64)"

    def uses_time(self, exprs) -> bool:
        """Whether ``t`` must be read (converted) before the expressions use it."""
        return self.mp and any(t in sp.sympify(e).free_symbols for e in exprs)


NUMPY = Flavour(False, Scalar())
MPMATH = Flavour(True, Mpmath())
