"""Accumulating switches (Zeno), detected once for both integrators.

Switches that accumulate are never counted to a cap: when `ZENO_SWITCHES` switches
fall within `ZENO_WINDOW` (relative to the time), the run is chattering on one
surface. On ``Vr = 0`` with friction that holds the mass (``|a_free| <= mu_s F``,
`cone_holds`), the limit of that chattering is Filippov's sliding motion, which is
the stick mode: the integrator enters it. Anywhere else the run stops with status
``"zeno"`` and a message naming the surface and the time.
"""

from __future__ import annotations

from collections import deque

from numpy.typing import ArrayLike

from .switching import Mode, Switching

__all__ = ["ZENO_SWITCHES", "ZENO_WINDOW", "Zeno", "cone_holds"]

ZENO_SWITCHES = 8
ZENO_WINDOW = 1e-9


def cone_holds(sw: Switching, t: float, y: ArrayLike) -> bool:
    """Whether friction holds the mass at this state: ``mu_s F > 0`` beyond rounding and
    ``|a_free| <= mu_s F`` within it (both stick limits non-negative).

    Chattering on ``Vr = 0`` converges to Filippov's sliding motion only there; a run
    that chatters outside the cone is not chattering in exact arithmetic, and stops.

    Parameters
    ----------
    sw : Switching
        The model's switching rules.
    t : float
        The time [s].
    y : array_like
        The state ``[X1, X1', X2, X2']``.

    Returns
    -------
    bool
        Whether the state lies in the friction cone.

    See Also
    --------
    beltmdsm.integrate.zeno.Zeno : Enters stick where this holds.

    Examples
    --------
    At the unforced equilibrium static friction holds the mass; without friction
    (``mu_s = 0``) the cone is empty:

    >>> from beltmdsm.model import Model

    >>> from beltmdsm.excitation import initial_state
    >>> y = initial_state(Model(Vb=0.0, alpha=0.0))
    >>> [cone_holds(Switching(Model(Vb=0.0, alpha=0.0, mu_s=mu_s)), 0.0, y) for mu_s in (0.4, 0.0)]
    [True, False]
    """
    h, tol = sw.ties(t, y)
    return bool(h[1] + h[2] > tol[1] + tol[2] and h[1] >= -tol[1] and h[2] >= -tol[2])


class Zeno:
    """The last `ZENO_SWITCHES` switch times of a run, and what an accumulation means.

    ``entered`` counts the chattering limits resolved as stick (a run's ``n_zeno``).

    Parameters
    ----------
    sw : Switching
        The model's switching rules.

    See Also
    --------
    beltmdsm.integrate.zeno.cone_holds : Where chattering becomes stick.

    Examples
    --------
    Eight switches on ``Vr = 0`` within 1e-11 s at a state inside the friction cone:
    the eighth enters stick; at a state outside it, the run stops with a message.

    >>> from beltmdsm.model import Model

    >>> from beltmdsm.excitation import initial_state
    >>> model = Model(Vb=0.0, alpha=0.0)
    >>> y = initial_state(model)
    >>> zeno = Zeno(Switching(model))
    >>> modes = [zeno.after(1 + k * 1e-12, "vr_zero", "relative_velocity", y, Mode.SLIP_BACK)
    ...          for k in range(8)]
    >>> modes[-1].name, zeno.entered
    ('STICK', 1)
    >>> zeno = Zeno(Switching(model.replace(mu_s=0.0)))
    >>> print([zeno.after(1 + k * 1e-12, "vr_zero", "relative_velocity", y, Mode.SLIP_BACK)
    ...        for k in range(8)][-1])
    switches accumulate on the relative_velocity surface at t = 1 s (8 within 7e-12 s); stopped
    """

    def __init__(self, sw: Switching) -> None:
        self.sw = sw
        self.recent: deque[float] = deque(maxlen=ZENO_SWITCHES)
        self.entered = 0
        self.entered_at: float | None = None

    def after(self, t: float, kind: str, surface: str, y: ArrayLike, new: Mode) -> Mode | str:
        """The mode after a switch at ``t`` to ``new``, or the message of a Zeno stop.

        Returns ``new`` unless switches accumulate: then ``Mode.STICK`` inside the
        friction cone on ``Vr = 0``, else a str saying where the run stops. A stick
        entered so that ends within `ZENO_WINDOW` and accumulates again has not
        resolved the chattering (the stick's own end condition and `cone_holds`
        disagree, at tolerances too loose to locate the switches): the run stops
        there too, instead of entering and leaving stick at one time for ever.
        """
        self.recent.append(t)
        window = ZENO_WINDOW * max(1.0, abs(t))
        if len(self.recent) < ZENO_SWITCHES or t - self.recent[0] > window:
            return new
        if kind == "vr_zero" and cone_holds(self.sw, t, y):
            if self.entered_at is not None and t - self.entered_at <= window:
                return (
                    f"switches accumulate on the {surface} surface at t = {t:.9g} s "
                    "again right after the stick entered there ended (the tolerances "
                    "are too loose to tell whether friction holds the mass); stopped"
                )
            self.entered += 1
            self.entered_at = t
            self.recent.clear()
            return Mode.STICK
        return (
            f"switches accumulate on the {surface} surface at t = {t:.9g} s "
            f"({ZENO_SWITCHES} within {t - self.recent[0]:.2g} s); stopped"
        )
