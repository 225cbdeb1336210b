"""Parameters, initial state and modes of a simulation of Eq. (4).

`resolve_parameters` completes and checks a parameter set once and `initial_state`
is the unforced equilibrium of Eq. (9) (both in `runtime.parameters`). The modes of
the hybrid system come from `generated.hybrid` (`runtime.switching.Mode`); the
names below are kept for the code that uses them.
"""

from __future__ import annotations

from generated import hybrid

from .parameters import CONTACTS, initial_state, resolve_parameters
from .switching import MODE_NAMES, Mode

__all__ = [
    "CONTACTS",
    "TENSIONS",
    "resolve_parameters",
    "initial_state",
    "Mode",
    "MODE_NAMES",
    "SLIP_BACK",
    "SLIP_FORWARD",
    "STICK",
    "FLIGHT",
    "SEPARATED",
]

TENSIONS = tuple(hybrid.GUARDS)

SLIP_BACK, SLIP_FORWARD, STICK = Mode.SLIP_BACK, Mode.SLIP_FORWARD, Mode.STICK
FLIGHT, SEPARATED = Mode.FLIGHT, Mode.SEPARATED
