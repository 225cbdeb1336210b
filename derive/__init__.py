"""Symbolic derivations of the forced 2-DOF mass-on-belt model, and the code generator.

Modules, one per concept (the paper's equations they implement in their docstrings):
``parameters`` (the parameter table), ``model`` (Eqs. 1-4), ``statespace``
(Eqs. 5-12), ``dynamics`` (Eq. 4 for simulation), ``modules`` (what generated/
contains), ``codegen`` (writes generated/), ``cli`` (``python -m derive``).
"""
