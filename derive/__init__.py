"""Symbolic derivations of the forced 2-DOF mass-on-belt model, and the code generator.

Modules, one per concept (the paper's equations they implement in their docstrings):
``parameters`` (the model's own parameters), ``laws`` (the registry of friction,
contact and tension laws, with their parameters), ``units`` (the contact law's units),
``model`` (Eqs. 1-4 from the chosen laws), ``statespace`` (Eqs. 5-12), ``dynamics``
(Eq. 4 for simulation), ``hybrid`` (modes, surfaces, saltation), ``oscillator``,
``fit`` (Eqs. 16-17), ``mdsm`` (Eqs. 13-21, A1-A2), ``averaging`` (a law over a fast
period), ``friction`` (Eqs. 23-25), ``stability`` (Eqs. 22, 26-28, A3-A8),
``correlation`` (the consistent MDSM), ``contraction`` (with ``contraction_energy``
and ``contraction_sign``, its steps), ``capabilities`` (what each choice of laws
allows), ``dop853`` (the integrator's tableau, as published), ``modules`` (what
generated/ contains), ``codegen`` (writes
generated/), ``paper`` and ``paper_check`` (the paper check), ``commands`` (what
the command line's derive commands run: `beltmdsm.cli.tree`).

A source checkout keeps derive/ beside beltmdsm/ and an installed package inside it;
either way it is imported as ``beltmdsm.derive`` (beltmdsm/_layout.py). By its old
top-level name it refuses: a second name would load a second copy of every module, and
of the law registry. ``python -m derive`` from a checkout's root still runs (its
``__main__`` runs ``python -m beltmdsm``, importing nothing of derive/ by the old name).
"""

import sys

if __name__ != "beltmdsm.derive" and not (__name__ == "derive" and sys.argv[:1] == ["-m"]):
    raise ImportError(
        f"derive/ is the package beltmdsm.derive: import it by that name, not as "
        f"{__name__!r} (a second name would load a second copy of the law registry)"
    )
