"""Across the onset of stick on a branch of cycles (`beltmdsm.cycles.continuation`).

Where the largest ``Vr`` of a pure-slip cycle reaches 0 (grazing-sliding) the cycle's
map has a kink: beyond it a stick phase zeroes the velocity perturbation, and its
Jacobian jumps. Newton's method started across the kink alternates between the two
sides, and at a nonsmooth fold (Stribeck's law: the pure-slip and the stick-slip
cycles both lie below the onset) both lie close on every hyperplane of the arclength.
So the onset is crossed in three steps: `stick_ahead` sees it coming (`measure`
extrapolated from the last two cycles); `locate` solves cycles of the side the branch
is on at safe distances and extrapolates them to the onset; `cross_stick` steps off
the grazing cycle onto the other side (the null vector of the Jacobian taken on that
side; onto the sliding side the cycle with ``max Vr = -delta``, the one of the two that
has it).
"""

from __future__ import annotations

import math

import numpy as np

from ..continuation.branch_result import LOCATE_TOL, SpecialPoint
from ..errors import NoPeriodicResponse
from ..integrate.switching import Mode

__all__ = ["measure", "stick_ahead", "locate", "cross_stick", "sticks"]


def sticks(img) -> int:
    """The stick phases entered in a cycle's run.

    Parameters
    ----------
    img : FlowImage
        The end of a run over one period (`beltmdsm.cycles.flow.CycleFlow.image`).

    Returns
    -------
    int
        How many switches enter stick.

    See Also
    --------
    beltmdsm.cycles.flow.orbit_observables : Counts them too, with the reversals.

    Examples
    --------
    The cycle at ``Vb = 1.5`` (period 6.654 s) sticks once a period:

    >>> from beltmdsm.cycles.flow import CycleFlow
    >>> from beltmdsm.model import Model
    >>> flow = CycleFlow(Model(friction="stribeck", alpha=0.0), "Vb")
    >>> x = np.array([2.902211983923, -2.033757676987, 11.547447572261, 0.0])
    >>> sticks(flow.image(x, 6.654341995080, 1.5, monodromy=False))
    1
    """
    return sum(1 for _, _, new in img.run.events if Mode(int(new)) == Mode.STICK)


def stick_ahead(cont, points, ds) -> float | None:
    """The arclength ahead at which `measure` of the last two cycles (one side),
    extrapolated, reaches 0, where that is within ``2 ds``; else None.

    Parameters
    ----------
    cont : Continuation
        The continuation.
    points : list of CyclePoint
        The branch so far; the last two are extrapolated.
    ds : float
        The current arclength step.

    Returns
    -------
    float or None
        The scaled arclength from the last point to the onset.

    See Also
    --------
    beltmdsm.cycles.stick.cross_stick : Crosses it.

    Examples
    --------
    On the subcritical Stribeck branch (born at ``Vb = 1.9957``) the sliding cycles'
    largest ``Vr`` rises to 0 at ``Vb = 2.9004``: two sliding cycles just below it,
    continued in a `beltmdsm.cycles.continuation.Continuation` as
    `beltmdsm.cycles.branch.cycle_branch` does:

    >>> import math
    >>> from beltmdsm.cycles.continuation import Continuation
    >>> from beltmdsm.cycles.flow import CycleFlow
    >>> from beltmdsm.model import Model
    >>> flow = CycleFlow(Model(friction="stribeck", alpha=0.0), "Vb")
    >>> x1 = [3.033451549774, -2.881366210888, 11.547447572261, 0.0]
    >>> x2 = [3.040910146986, -2.919995555294, 11.547447572261, 0.0]
    >>> cont = Continuation(flow, 1.99, 3.0, 12.5474, 2 * math.pi, x2, 2.889932446323)
    >>> def cycle_at(x, T, p):  # the cycle at p fixed, and the tangent towards a larger p
    ...     z, row = cont.z_of(x, T, p), np.eye(6)[5]
    ...     x, T, p, image, J, _ = cont.correct(z, lambda q: (float(q[5] - z[5]), row))
    ...     tangent = cont.tangent(J, sign=1.0)
    ...     tangent = tangent if tangent[-1] > 0 else -tangent
    ...     return cont.point(x, T, p, image, tangent[-1], J), tangent
    >>> q1, _ = cycle_at(x1, 6.342539720071, 2.869734936938)
    >>> q2, tangent = cycle_at(x2, 6.343660474058, 2.889932446323)
    >>> round(measure(q1, False), 4), round(measure(q2, False), 4)
    (-0.0254, -0.0086)
    >>> ahead = stick_ahead(cont, [q1, q2], 0.1)
    >>> round(ahead, 3), stick_ahead(cont, [q1, q2], 0.01)  # too far for a step of 0.01
    (0.102, None)
    """
    if len(points) < 2 or (points[-2].n_sticks > 0) != (points[-1].n_sticks > 0):
        return None
    (q1, q2) = points[-2:]
    sticking = q2.n_sticks > 0
    f1, f2 = measure(q1, sticking), measure(q2, sticking)
    dist = float(np.linalg.norm(cont.z(q2) - cont.z(q1)))
    if not (f2 > f1 and dist > 0):
        return None
    s = -f2 / (f2 - f1) * dist
    return s if s <= 2 * ds else None


def measure(point, sticking: bool) -> float:
    """How far a cycle is from the stick onset, negative on its side and 0 there: the
    largest Vr of a sliding cycle; minus the squared stick time of a stick-slip one
    (the stick phase of a grazing-sliding orbit lasts as the square root of the
    distance).

    Parameters
    ----------
    point : CyclePoint or Observables
        A cycle (its ``max_relative_velocity`` and ``stick_time``).
    sticking : bool
        Whether the cycle has a stick phase.

    Returns
    -------
    float
        Negative on the cycle's side of the onset, 0 at it.

    See Also
    --------
    beltmdsm.cycles.stick.stick_ahead : Extrapolates it.

    Examples
    --------
    A sliding cycle whose largest ``Vr`` is -0.0086, and a stick-slip one stuck for
    1.52 s a period (the cycle at ``Vb = 1.5``):

    >>> from types import SimpleNamespace
    >>> measure(SimpleNamespace(max_relative_velocity=-0.0086, stick_time=0.0), False)
    -0.0086
    >>> round(measure(SimpleNamespace(max_relative_velocity=0.0, stick_time=1.52), True), 4)
    -2.3104
    """
    return -(point.stick_time**2) if sticking else point.max_relative_velocity


def _on_side(point, sticking: bool) -> bool:
    return (point.n_sticks > 0) == sticking and measure(point, sticking) < 0


def locate(cont, prev, tangent, s_onset):
    """The stick onset ahead of ``prev`` (sliding or sticking), about ``s_onset`` along
    ``tangent``.

    Cycles of ``prev``'s side are solved at safe distances short of the onset (near
    it, on a hyperplane of the arclength, Newton's method may land on a cycle of the
    other side as well: at a nonsmooth fold both lie on the same side of the
    parameter), and ``p``, ``s`` and the state are extrapolated to `measure` = 0 by
    quadratics in it; the accuracy is the difference from the linear extrapolation
    through the nearest two. The distances shrink by 4 until it is below
    ``LOCATE_TOL / 10``.

    Parameters
    ----------
    cont : Continuation
        The continuation.
    prev : CyclePoint
        The last cycle before the onset.
    tangent : numpy.ndarray, shape (6,)
        The unit tangent there.
    s_onset : float
        The estimate of `stick_ahead`.

    Returns
    -------
    tuple or None
        ``(value, accuracy, nearest point of prev's side, scaled state at the
        onset)``, or None where fewer than three such cycles are found.

    See Also
    --------
    beltmdsm.cycles.stick.cross_stick : Goes on to the other side.

    Examples
    --------
    On the subcritical Stribeck branch (born at ``Vb = 1.9957``) the sliding cycles'
    largest ``Vr`` rises to 0 at ``Vb = 2.9004``: two sliding cycles just below it,
    continued in a `beltmdsm.cycles.continuation.Continuation` as
    `beltmdsm.cycles.branch.cycle_branch` does:

    >>> import math
    >>> from beltmdsm.cycles.continuation import Continuation
    >>> from beltmdsm.cycles.flow import CycleFlow
    >>> from beltmdsm.model import Model
    >>> flow = CycleFlow(Model(friction="stribeck", alpha=0.0), "Vb")
    >>> x1 = [3.033451549774, -2.881366210888, 11.547447572261, 0.0]
    >>> x2 = [3.040910146986, -2.919995555294, 11.547447572261, 0.0]
    >>> cont = Continuation(flow, 1.99, 3.0, 12.5474, 2 * math.pi, x2, 2.889932446323)
    >>> def cycle_at(x, T, p):  # the cycle at p fixed, and the tangent towards a larger p
    ...     z, row = cont.z_of(x, T, p), np.eye(6)[5]
    ...     x, T, p, image, J, _ = cont.correct(z, lambda q: (float(q[5] - z[5]), row))
    ...     tangent = cont.tangent(J, sign=1.0)
    ...     tangent = tangent if tangent[-1] > 0 else -tangent
    ...     return cont.point(x, T, p, image, tangent[-1], J), tangent
    >>> q1, _ = cycle_at(x1, 6.342539720071, 2.869734936938)
    >>> q2, tangent = cycle_at(x2, 6.343660474058, 2.889932446323)
    >>> value, accuracy, near, z_onset = locate(cont, q2, tangent, stick_ahead(cont, [q1, q2], 0.1))
    >>> round(value, 6), accuracy < 1e-6, near.n_sticks
    (2.900393, True, 0)
    """
    sticking = prev.n_sticks > 0
    s_g, D = s_onset, min(0.5 * s_onset, 4e-3)
    good = []
    value, accuracy, zg = prev.value, math.inf, None
    for _ in range(6):
        stuck = False
        for frac in (1.0, 0.5, 0.25):
            s = s_g - frac * D
            if s <= 0 or any(abs(s - q) < 1e-15 for q, _ in good):
                continue
            try:
                pt = cont.trial(prev, tangent, s)
            except NoPeriodicResponse:
                stuck = True
                continue
            if not _on_side(pt, sticking):
                stuck = True
                continue
            good.append((s, pt))
        if stuck and len(good) < 3:
            s_g -= D  # the estimate lies beyond the onset
            continue
        if len(good) < 3:
            return None
        near = sorted(good, key=lambda g: g[0])[-3:]
        f = np.array([measure(q, sticking) for _, q in near])
        p = np.array([q.value for _, q in near])
        value = float(np.polyval(np.polyfit(f, p, 2), 0.0))
        accuracy = abs(value - float(np.polyval(np.polyfit(f[1:], p[1:], 1), 0.0)))
        Z = np.array([cont.z(q) for _, q in near])
        zg = np.array([np.polyval(np.polyfit(f, Z[:, i], 2), 0.0) for i in range(Z.shape[1])])
        if accuracy <= 0.1 * LOCATE_TOL:
            break
        s_g = float(np.polyval(np.polyfit(f, [g for g, _ in near], 2), 0.0))
        D *= 0.25
    if zg is None:
        return None
    return value, accuracy, near[-1][1], zg


def cross_stick(cont, prev, tangent, s_onset):
    """Locate the stick onset ahead of ``prev`` and step onto the cycles of the other side.

    Across the onset the map has another Jacobian (a stick phase zeroes the velocity
    perturbation), so Newton's method started across the kink alternates between the
    two sides. The tangent of the other side's branch is the null vector of the
    Jacobian taken just on that side of the grazing cycle; of its two directions, the
    one along the branch so far goes first (the branch goes on), the other second (it
    turns back at the onset: a nonsmooth fold).

    Parameters
    ----------
    cont : Continuation
        The continuation.
    prev : CyclePoint
        The last cycle before the onset.
    tangent : numpy.ndarray, shape (6,)
        The unit tangent there.
    s_onset : float
        The estimate of `stick_ahead`.

    Returns
    -------
    tuple or None
        ``(special point, nearest point before, first point after, tangent)``, or
        None.

    See Also
    --------
    beltmdsm.cycles.stick.locate : The onset itself.
    beltmdsm.cycles.continuation.walk : Calls it where a step changes the stick phases.

    Examples
    --------
    On the subcritical Stribeck branch (born at ``Vb = 1.9957``) the sliding cycles'
    largest ``Vr`` rises to 0 at ``Vb = 2.9004``: two sliding cycles just below it,
    continued in a `beltmdsm.cycles.continuation.Continuation` as
    `beltmdsm.cycles.branch.cycle_branch` does:

    >>> import math
    >>> from beltmdsm.cycles.continuation import Continuation
    >>> from beltmdsm.cycles.flow import CycleFlow
    >>> from beltmdsm.model import Model
    >>> flow = CycleFlow(Model(friction="stribeck", alpha=0.0), "Vb")
    >>> x1 = [3.033451549774, -2.881366210888, 11.547447572261, 0.0]
    >>> x2 = [3.040910146986, -2.919995555294, 11.547447572261, 0.0]
    >>> cont = Continuation(flow, 1.99, 3.0, 12.5474, 2 * math.pi, x2, 2.889932446323)
    >>> def cycle_at(x, T, p):  # the cycle at p fixed, and the tangent towards a larger p
    ...     z, row = cont.z_of(x, T, p), np.eye(6)[5]
    ...     x, T, p, image, J, _ = cont.correct(z, lambda q: (float(q[5] - z[5]), row))
    ...     tangent = cont.tangent(J, sign=1.0)
    ...     tangent = tangent if tangent[-1] > 0 else -tangent
    ...     return cont.point(x, T, p, image, tangent[-1], J), tangent
    >>> q1, _ = cycle_at(x1, 6.342539720071, 2.869734936938)
    >>> q2, tangent = cycle_at(x2, 6.343660474058, 2.889932446323)
    >>> found = cross_stick(cont, q2, tangent, stick_ahead(cont, [q1, q2], 0.1))
    >>> onset, before, after, new_tangent = found
    >>> onset.kind, round(onset.value, 6), onset.stable_before, onset.stable_after
    ('stick_onset', 2.900393, False, True)
    >>> after.n_sticks, bool(new_tangent[-1] < 0)  # stick-slip cycles, back to lower Vb
    (1, True)
    >>> print(onset.detail)  # doctest: +NORMALIZE_WHITESPACE
    the largest Vr reaches 0: a stick phase appears (grazing-sliding);
    the branch turns back there (a nonsmooth fold)
    """
    sticking = prev.n_sticks > 0
    located = locate(cont, prev, tangent, s_onset)
    if located is None:
        return None
    value, accuracy, near, zg = located
    # off the grazing cycle to the other side: along the tangent, or the section's
    # coordinate x_k towards a larger |Vr| (to stick) or a smaller one (to slide)
    e_k = np.zeros(zg.size)
    e_k[cont.flow.k] = 1.0 if sticking else -1.0
    offsets = [eps * d for eps in (1e-7, 1e-6, 1e-5, 1e-4) for d in (tangent, -tangent, e_k)]
    for offset in offsets:
        x, T, p = cont.unpack(zg + offset)
        try:
            img = cont.flow.image(x, T, p)
        except NoPeriodicResponse:
            continue
        if (sticks(img) > 0) != sticking:
            break
    else:
        return None
    if sticking:
        return _slide_off(cont, zg, value, accuracy, near, tangent)
    tk = cont.tangent(cont.jacobian(x, T, p, img), tangent)
    for sign in (1.0, -1.0):
        for step in (1e-3, 1e-4, 1e-5):
            z_pred = zg + sign * step * tk
            try:
                x, T, p, img, J, _ = cont.correct(z_pred, cont.arclength(z_pred, sign * tk))
            except NoPeriodicResponse:
                continue
            z = cont.z_of(x, T, p)
            if float(np.linalg.norm(z - zg)) < 0.5 * step:
                continue
            t_new = cont.tangent(J, sign * tk)
            pt = cont.point(x, T, p, img, t_new[-1], J)
            if (pt.n_sticks > 0) == sticking:
                continue
            turns = tangent[-1] * t_new[-1] < 0
            detail = (
                "the largest Vr reaches 0: a stick phase "
                + ("disappears" if sticking else "appears")
                + " (grazing-sliding)"
                + ("; the branch turns back there (a nonsmooth fold)" if turns else "")
            )
            sp = SpecialPoint(
                "stick_onset",
                value,
                accuracy,
                None,
                near.multipliers,
                near.stable,
                pt.stable,
                detail,
            )
            return sp, near, pt, t_new
    return None


def _largest_vr_row(cont, target):
    """The extra equation ``max Vr(z) = target`` for `Continuation.correct` (gradient by
    central differences): it holds on sliding cycles only (a stick-slip one has 0)."""

    def value(z):
        return cont.flow.largest_vr(*cont.unpack(z))

    def extra(z):
        row = np.empty(z.size)
        for i in range(z.size):
            h = 1e-7 * max(1.0, abs(z[i]))
            e = np.zeros(z.size)
            e[i] = h
            row[i] = (value(z + e) - value(z - e)) / (2 * h)
        return (value(z) - target) / cont.sx, row / cont.sx

    return extra


def _slide_off(cont, zg, value, accuracy, near, tangent):
    """From the grazing cycle ``zg`` reached on stick-slip cycles onto the sliding ones.

    Near the onset both branches lie close together on every hyperplane of the
    arclength, and Newton's method lands on the stick-slip one; the sliding cycle with
    ``max Vr = -delta`` is the one of the two that has it, so it is solved for
    instead, the parameter free, and the branch goes on from it away from ``zg``.
    """
    for delta in (1e-4, 1e-3, 1e-5):
        try:
            x, T, p, img, J, _ = cont.correct(
                zg, _largest_vr_row(cont, -delta * cont.sx), fresh=True
            )
        except NoPeriodicResponse:
            continue
        t_new = cont.tangent(J)
        z = cont.z_of(x, T, p)
        t_new = t_new if float(t_new @ (z - zg)) >= 0 else -t_new
        pt = cont.point(x, T, p, img, t_new[-1], J)
        if pt.n_sticks or pt.max_relative_velocity >= 0:
            continue
        turns = tangent[-1] * t_new[-1] < 0
        detail = "the largest Vr reaches 0: a stick phase disappears (grazing-sliding)" + (
            "; the branch turns back there (a nonsmooth fold)" if turns else ""
        )
        sp = SpecialPoint(
            "stick_onset", value, accuracy, None, near.multipliers, near.stable, pt.stable, detail
        )
        return sp, near, pt, t_new
    return None
