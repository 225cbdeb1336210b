"""Symbolic derivations of the forced 2-DOF mass-on-belt model, and the code generator.

Modules, one per concept (the paper's equations they implement in their docstrings):
``parameters`` (the model's own parameters), ``laws`` (the registry of friction,
contact and tension laws, with their parameters), ``units`` (the contact law's units),
``model`` (Eqs. 1-4 from the chosen laws), ``statespace`` (Eqs. 5-12), ``dynamics``
(Eq. 4 for simulation), ``hybrid`` (modes, surfaces, saltation), ``oscillator``,
``fit`` (Eqs. 16-17), ``mdsm`` (Eqs. 13-21, A1-A2), ``averaging`` (a law over a fast
period), ``friction`` (Eqs. 23-25), ``stability`` (Eqs. 22, 26-28, A3-A8),
``correlation`` (the consistent MDSM), ``contraction`` (with ``contraction_energy``
and ``contraction_sign``, its steps), ``capabilities`` (what each
choice of laws allows), ``dop853`` (the integrator's tableau, as published),
``modules`` (what generated/ contains), ``codegen`` (writes
generated/), ``paper`` and ``paper_check`` (the paper check),
``cli`` (``python -m derive``).
"""
