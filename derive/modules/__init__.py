"""What ``generated/`` contains: one spec module per generated module, and their registry.

This is the pipeline's last pure step: each spec module's ``build()`` calls the
derivations and packages their expressions as `codegen.FunctionSpec` specs of one
generated module (``derive/modules/unforced.py`` for ``generated/unforced.py``, ...).
Nothing here writes files. The options ``friction=``, ``contact=`` and ``tension=``
of every function are the choices of the registry (`beltmdsm.derive.laws`), one variant per
choice, and a function takes an option only where its law enters
(`beltmdsm.derive.modules._shared`).
"""

from __future__ import annotations

import time

from ..codegen import ModuleSpec
from . import (
    capabilities,
    contraction,
    correlation,
    dynamics,
    fit,
    friction,
    hybrid,
    oscillator,
    stability,
    tableau,
    unforced,
)

__all__ = ["MODULES", "BUILDERS", "all_modules"]

#: The spec modules, in the order `all_modules` derives them.
MODULES = (
    unforced,
    dynamics,
    fit,
    friction,
    stability,
    correlation,
    hybrid,
    oscillator,
    capabilities,
    tableau,
    contraction,
)
#: Their builders, in that order.
BUILDERS = tuple(module.build for module in MODULES)


def all_modules(progress=None) -> tuple[ModuleSpec, ...]:
    """Every generated module's spec; ``progress(spec, seconds)`` is called after each."""
    specs = []
    for build in BUILDERS:
        start = time.perf_counter()
        specs.append(build())
        if progress is not None:
            progress(specs[-1], time.perf_counter() - start)
    return tuple(specs)
