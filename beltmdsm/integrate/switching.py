"""Which mode follows a switch: the guard table and Filippov's rules, on generated kernels.

Eq. (4) is a hybrid system (derive/hybrid.py, `beltmdsm.generated.hybrid`): modes with smooth
vector fields, switching surfaces, and a guard table per tension law saying which
surface ends which mode and what follows. Two targets of the table are rules, not
modes, and they live here, written in terms of the generated switching functions
only (no formula of the model):

* ``decide_slip``, at ``Vr = 0`` in contact (Filippov's convention for the
  set-valued friction of Eq. 3). With ``sf = mu_s F - a_free`` and
  ``sb = mu_s F + a_free`` (the ``stick_forward`` and ``stick_back`` surfaces; ``mu_s``
  stands for the law's static bound, which a law with a static coefficient above its
  kinetic one, ``static_kinetic``, gives apart from its slip law), the
  slip fields point at the surface from both sides exactly when ``sf >= 0`` and
  ``sb >= 0``: the mass sticks (under a static bound above the kinetic coefficient
  also where the slip fields alone would cross, ``mu_k F < |a_free| <= mu_s F``: the
  static friction holds it). Where ``sf < 0`` (``a_free > mu_s F``) it slips
  forward, where ``sb < 0`` backward, whether it crossed or started there.
  The friction cone is empty where ``mu_s F <= 0`` (no friction, or a pulling
  contact under ``tension="allowed"``): both fields then point away from the
  surface, and the stated rule is that the mass leaves along ``a_free``
  (``sb - sf = 2 a_free``), along the sign of its rate if ``a_free`` is zero, and
  backward (the belt's direction relative to the mass) if that is zero too.
* ``decide_contact``, on entering contact: separated (clipped law) while the
  contact force would pull, else the sign of ``Vr``, or ``decide_slip`` at
  ``Vr = 0``.

Ties are decided with a tolerance: a switching function is taken as zero within
`TIE_ULPS` ulps of its rounding scale (`beltmdsm.generated.hybrid.surface_scales`, the sum of
the absolute values of its terms). At a tie the rate of the function along the
candidate mode decides: a mass at the friction limit sticks if the margin grows and
slips if it shrinks. This is what makes a one-ulp difference between ``|a_free|``
and ``mu_s F`` (the paper's ``Vb = 0`` from rest) stick instead of chattering.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

from enum import IntEnum

import numpy as np
from numpy.typing import ArrayLike, NDArray

from beltmdsm.generated import hybrid

from ..model import Model
from ..settings import fastest_rate

__all__ = ["Mode", "MODE_NAMES", "SURFACE_INDEX", "TIE_ULPS", "EVENT_KINDS", "Switching"]

Mode = IntEnum("Mode", {name.upper(): code for name, code in hybrid.MODE_CODES.items()})
Mode.__doc__ = """Modes of Eq. (4) as a hybrid system (`beltmdsm.generated.hybrid.MODE_CODES`).

The slip codes are the friction direction sgn(Vr) of Eq. (3); a run's segments and
events carry these codes.

See Also
--------
beltmdsm.integrate.switching.MODE_NAMES : The short names used in tables.
beltmdsm.integrate.switching.Switching : Which mode follows a switch.

Examples
--------
>>> [(mode.name, int(mode)) for mode in Mode][:3]
[('SLIP_BACK', -1), ('STICK', 0), ('SLIP_FORWARD', 1)]
>>> MODE_NAMES[Mode.STICK], Mode(1) is Mode.SLIP_FORWARD
('stick', True)
"""
#: Short names used in summaries and tables.
MODE_NAMES = {
    Mode.SLIP_BACK: "slip-",
    Mode.SLIP_FORWARD: "slip+",
    Mode.STICK: "stick",
    Mode.FLIGHT: "flight",
    Mode.SEPARATED: "separated",
}
SURFACE_INDEX = {name: i for i, name in enumerate(hybrid.SURFACES)}
#: A switching function within this many ulps of its rounding scale counts as zero.
TIE_ULPS = 32
_EPS = np.finfo(float).eps
#: What a crossing is called in the event list: (surface, direction) -> kind.
EVENT_KINDS = {
    ("relative_velocity", 1): "vr_zero",
    ("relative_velocity", -1): "vr_zero",
    ("stick_forward", -1): "unstick",
    ("stick_back", -1): "unstick",
    ("penetration", -1): "lift_off",
    ("penetration", 1): "touch_down",
    ("contact_force", -1): "separation",
    ("contact_force", 1): "recontact",
}
_IN_CONTACT = (Mode.SLIP_BACK, Mode.STICK, Mode.SLIP_FORWARD)


class Switching:
    """The switching rules of one model (parameters, contact and tension law).

    Parameters
    ----------
    model : Model
        The parameters, contact law and tension law whose rules these are.

    Attributes
    ----------
    field, surfaces, scales, rates : generated ``_support.Bound`` kernels
        Plain Python (``backend="python"``): the rules run once per switch, where a
        numba kernel's dispatch costs about what the Python evaluation does (4 against
        6 us), while loading it from numba's cache costs a process about 0.1 s per
        kernel. The compiled integrators take only their ``args``: they compile the
        kernels into their own loops.
    guards : dict
        ``Mode -> (watch, dirs, targets)``: the indices of the surfaces that end the
        mode (int64 array), their crossing directions (float array) and the guard
        targets (mode names or rule names) of `beltmdsm.generated.hybrid.GUARDS`.

    See Also
    --------
    beltmdsm.integrate.zeno.Zeno : What an accumulation of switches means.
    beltmdsm.integrate.events.integrate_events : The integrator these rules drive.

    Examples
    --------
    At rest on the unforced equilibrium, a belt at rest leaves the mass stuck
    (``Vr = 0`` inside the friction cone); at ``Vb = 4`` it slips backward
    (``Vr = -4``):

    >>> from beltmdsm.excitation import initial_state
    >>> for Vb in (0.0, 4.0):
    ...     model = Model(Vb=Vb, alpha=0.0)
    ...     print(Vb, Switching(model).initial_mode(0.0, initial_state(model)).name)
    0.0 STICK
    4.0 SLIP_BACK
    """

    def __init__(self, model: Model) -> None:
        self.model, self.tension = model, model.tension
        self.field, self.surfaces, self.scales, self.rates = (
            bind(backend="python", **model.arguments(bind))
            for bind in (
                hybrid.bind_vector_field,
                hybrid.bind_surfaces,
                hybrid.bind_surface_scales,
                hybrid.bind_surface_rates,
            )
        )
        self.Vb = model["Vb"]
        self.rate = fastest_rate(model)
        self.guards = {}
        for name, guards in hybrid.GUARDS[model.tension].items():
            self.guards[Mode[name.upper()]] = (
                np.array([SURFACE_INDEX[s] for s, _, _ in guards], dtype=np.int64),
                np.array([float(d) for _, d, _ in guards]),
                tuple((s, d, target) for s, d, target in guards),
            )

    def ties(self, t: float, y: ArrayLike) -> tuple[NDArray[np.float64], list[float]]:
        """The switching functions at ``(t, y)`` and the tolerance of each (`TIE_ULPS`)."""
        h = self.surfaces(t, *y)
        tol = [TIE_ULPS * _EPS * s for s in self.scales(t, *y)]
        return h, tol

    def decide_slip(self, t: float, y: ArrayLike) -> Mode:
        """The mode at ``Vr = 0`` in contact (module docstring)."""
        h, tol = self.ties(t, y)
        sf, sb = h[1], h[2]
        tf, tb = tol[1], tol[2]
        if sf + sb > tf + tb:  # the friction can hold the mass
            if sf < -tf:
                return Mode.SLIP_FORWARD
            if sb < -tb:
                return Mode.SLIP_BACK
            if sf <= tf or sb <= tb:  # at a limit: does the margin shrink?
                r = self.rates(t, *y, float(Mode.STICK))
                if sf <= tf and r[1] < 0:
                    return Mode.SLIP_FORWARD
                if sb <= tb and r[2] < 0:
                    return Mode.SLIP_BACK
            return Mode.STICK
        a_free, tol_a = 0.5 * (sb - sf), 0.5 * (tf + tb)
        if abs(a_free) <= tol_a:
            r = self.rates(t, *y, float(Mode.STICK))
            a_free = 0.5 * (r[2] - r[1])
        return Mode.SLIP_FORWARD if a_free > 0 else Mode.SLIP_BACK

    def pulls(self, t: float, y: ArrayLike) -> bool | np.bool_:
        """Whether Eq. (1) would pull at this state in contact (the clipped law separates).

        At a tie, whether the force is falling through zero along the contact field.
        """
        h, tol = self.ties(t, y)
        if abs(h[4]) <= tol[4]:
            return self.rates(t, *y, float(Mode.SLIP_BACK))[4] < 0
        return h[4] < 0

    def decide_contact(self, t: float, y: ArrayLike) -> Mode:
        """The mode on entering contact (module docstring)."""
        if self.tension == "clipped" and self.pulls(t, y):
            return Mode.SEPARATED
        return self.by_relative_velocity(t, y)

    def by_relative_velocity(self, t: float, y: ArrayLike) -> Mode:
        """The mode in contact: slip along the sign of ``Vr``, `decide_slip` at ``Vr = 0``."""
        h, tol = self.ties(t, y)
        if h[0] > tol[0]:
            return Mode.SLIP_FORWARD
        if h[0] < -tol[0]:
            return Mode.SLIP_BACK
        return self.decide_slip(t, y)

    def initial_mode(self, t: float, y: ArrayLike) -> Mode:
        """The mode of a state at the start of a run."""
        if y[2] < 0 or (y[2] == 0 and y[3] <= 0):
            return Mode.FLIGHT
        return self.decide_contact(t, y)

    def target(self, mode: Mode, guard: int, t: float, y: ArrayLike) -> Mode:
        """The mode after crossing guard number ``guard`` of ``mode``."""
        target = self.guards[mode][2][guard][2]
        if target == hybrid.DECIDE_SLIP:
            return self.decide_slip(t, y)
        if target == hybrid.DECIDE_CONTACT:
            return self.decide_contact(t, y)
        return Mode[target.upper()]

    def holds(self, mode: Mode, guard: int, t: float, y: ArrayLike) -> NDArray[np.float64] | None:
        """Where friction still holds a mass whose stick limit was crossed: the state put
        back inside the limit, or None where the mass slips.

        A crossing lies on its limit within the tie; where the limit's rate along stick
        is not negative beyond its rounding (`TIE_ULPS` ulps of the limit's scale per
        ``1 / fastest_rate``), the margin is not shrinking: a mass at rest exactly on
        the friction limit, the rounding of the normal motion taking the margin an ulp
        below zero and back, stays stuck. The state is then moved by the fewest ulps of
        ``X1`` (at most `TIE_ULPS`) that make the margin positive, as `project` puts a
        crossing exactly on its surface, so that the integrator starts inside the mode.
        """
        surface = self.guards[mode][2][guard][0]
        if mode != Mode.STICK or surface not in ("stick_forward", "stick_back"):
            return None
        i = SURFACE_INDEX[surface]
        h, tol = self.ties(t, y)
        if h[1] + h[2] <= tol[1] + tol[2] or abs(h[i]) > tol[i]:
            return None
        if self.rates(t, *y, float(Mode.STICK))[i] < -tol[i] * self.rate:
            return None
        for direction in (np.inf, -np.inf):
            moved = np.array(y, dtype=float)
            for _ in range(TIE_ULPS):
                moved[0] = np.nextafter(moved[0], direction)
                if self.surfaces(t, *moved)[i] > 0:
                    return moved
        return None

    def project(self, mode: Mode, guard: int, y: ArrayLike) -> NDArray[np.float64]:
        """``y`` put exactly on the surface it has crossed, where that is a coordinate.

        ``Vr = 0`` and ``X2 = 0`` hold exactly at their switches; the located time
        is within the root finder's tolerance, and a state on the wrong side by a
        rounding would start the next mode across its own surface.
        """
        surface = self.guards[mode][2][guard][0]
        y = np.array(y, dtype=float)
        if surface == "relative_velocity":
            y[1] = self.Vb
        elif surface == "penetration":
            y[2] = 0.0
        return y

    def kind(self, mode: Mode, guard: int) -> str:
        """The event kind of a crossing (`EVENT_KINDS`)."""
        surface, direction, _ = self.guards[mode][2][guard]
        return EVENT_KINDS[(surface, direction)]

    @staticmethod
    def in_contact(mode: Mode) -> bool:
        return mode in _IN_CONTACT
