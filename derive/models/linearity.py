"""Whether a model's slip field is linear: the fact that decides a degenerate Hopf point.

Where the field of each slip mode, with the excitation off, is affine in the state
(``f = A y + b``), steady sliding's Hopf point is a linear centre: its pure-slip cycles
exist at one parameter value only, of every amplitude up to the one that grazes
``v_r = 0`` (`beltmdsm.oscillator.hopf_branch`). That holds under a law whose slip
coefficient is constant (Coulomb's, static/kinetic's) with a normal force affine in the
state (a constant load, Hoffmann's spring and preload), not under Stribeck's law nor the
paper's Hertz-Damp contact.

SymPy decides it: the Jacobian ``d f / d y`` of both slip modes' fields (``1`` and
``-1``, the excitation amplitudes set to 0) holds no state symbol once expanded. A state
symbol that stays after the expansion (a cancellation SymPy does not see) counts as
nonlinear: the runtime then takes the general path of a Hopf point, never the centre's.
"""

from __future__ import annotations

import sympy as sp

from .system import System

__all__ = ["linear_slip"]


def linear_slip(s: System) -> bool:
    """Whether both slip modes' unforced fields of ``s`` are affine in the state."""
    state = set(s.state)
    for mode in (1, -1):
        J = s.fields[mode].subs(s.unforced).jacobian(s.state)
        if any(sp.expand(e).free_symbols & state for e in J):
            return False
    return True
