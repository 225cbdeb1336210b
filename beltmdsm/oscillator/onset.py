"""The onset of stick: a pure-slip cycle followed in a parameter to where its least slip
speed reaches 0 (the cycle grazes ``v_r = 0``).
"""

from __future__ import annotations

import numpy as np

from ..errors import NoPeriodicResponse
from .cycle import Cycle
from .slip_shooting import _shoot_slip

__all__ = ["stick_onset"]

#: The bracket of the stick onset, relative, where the last pure-slip cycle is taken.
_BRACKET = 1e-10


def stick_onset(
    cycle: Cycle, parameter: str, step: float, *, tol: float = 1e-12, max_iter: int = 40
) -> Cycle:
    """The pure-slip cycle where its least slip speed reaches 0: the onset of stick.

    From ``cycle`` (pure slip) the parameter moves by ``step`` towards the onset, then
    by the secant of the least slip speed ``m v_r`` (the slip velocity on the cycle's
    section), each cycle shot from the one before; a value where no pure-slip cycle is
    found (past the onset) is halved back.

    Parameters
    ----------
    cycle : Cycle
        A pure-slip cycle.
    parameter : str
    step : float
        The first step in the parameter, towards the onset.
    tol : float
        The least slip speed at the onset, relative to ``1 + |state|``.
    max_iter : int

    Returns
    -------
    Cycle
        The grazing cycle; ``cycle.system.params[parameter]`` is the onset.

    Raises
    ------
    ValueError
        A cycle with a stick, or an unknown parameter.
    NoPeriodicResponse
        No onset within ``max_iter`` steps.

    See Also
    --------
    self_excited_cycle : the cycle to start from.

    Examples
    --------
    >>> from beltmdsm.oscillator import System, self_excited_cycle
    >>> slip = self_excited_cycle(System("belt_1dof", friction="stribeck", Vb=2.5),
    ...                           [3.0182035, 2.0991444], 6.3203187)
    >>> onset = stick_onset(slip, "Vb", 0.2)
    >>> round(onset.system.params["Vb"], 6)
    2.900393
    """
    if cycle.sticks or cycle.switches:
        raise ValueError("cycle: has switches; the stick onset starts from a pure-slip cycle")
    if parameter not in cycle.system.params:
        raise ValueError(f"parameter={parameter!r}: not a parameter of {cycle.system!r}")

    def speed(c):
        k = c.system.kernels
        return c.mode * k.slip_velocity(0.0, c.state, c.system.p)

    good = [(cycle.system.params[parameter], speed(cycle), cycle)]
    value = good[-1][0] + step
    for _ in range(max_iter):
        last = good[-1][2]
        try:
            c = _shoot_slip(
                last.system.replace(**{parameter: value}),
                last.state,
                last.period,
                30,
                dict(rtol=1e-11, atol=1e-11),
            )
        except NoPeriodicResponse:
            # past the onset (the run grazes or sticks): bisect back; a bracket that has
            # shrunk to 1e-10 leaves the last pure-slip cycle as the grazing one (its
            # least slip speed is then below the integration's resolution of a switch)
            if abs(value - good[-1][0]) <= _BRACKET * (1.0 + abs(value)):
                return good[-1][2]
            value = 0.5 * (value + good[-1][0])
            continue
        good.append((value, speed(c), c))
        if abs(good[-1][1]) <= tol * (1.0 + np.abs(c.state).max()):
            return c
        (v0, s0, _), (v1, s1, _) = good[-2], good[-1]
        if abs(v1 - v0) <= _BRACKET * (1.0 + abs(v1)):
            return c  # the secant moves below the parameter's resolution: at the onset
        value = v1 - s1 * (v1 - v0) / (s1 - s0)
    raise NoPeriodicResponse(
        f"{cycle.system!r}: no stick onset in {parameter} found in {max_iter} steps"
    )
