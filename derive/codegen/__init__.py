"""Code generation: SymPy expressions to plain numpy and mpmath modules in ``generated/``.

One module per concept:

* `beltmdsm.derive.codegen.specs`: what a generated function and module contain (data);
* `beltmdsm.derive.codegen.printers`: the numpy, scalar and mpmath printers (roots, quadratures);
* `beltmdsm.derive.codegen.variants`: a function's implementations, one per distinct variant
  (CSE, numpy, scalar and mpmath code) and its dispatch table;
* `beltmdsm.derive.codegen.docstrings`: the numpydoc docstrings of a function and its binder;
* `beltmdsm.derive.codegen.render`: the public functions and whole modules, deterministically;
* `beltmdsm.derive.codegen.files`: where ``generated/`` is, writing it and the staleness check
  (the only place in the package that writes files).
"""

from .files import GENERATED, HEADER, source_checkout, stale, write
from .render import render, render_all
from .specs import FunctionSpec, ModuleSpec, NoVariant

__all__ = [
    "FunctionSpec",
    "ModuleSpec",
    "NoVariant",
    "render",
    "render_all",
    "write",
    "stale",
    "GENERATED",
    "HEADER",
    "source_checkout",
]
