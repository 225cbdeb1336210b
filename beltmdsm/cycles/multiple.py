"""A branch of cycles on from where single shooting's conditioning fails.

`beltmdsm.cycles.continuation.CycleProblem` shoots over one period; a cycle whose
largest multiplier passes `MULTIPLIER_LIMIT` amplifies the run's errors past Newton's
tolerance there (Stribeck's law continued in ``v_s`` at ``Vb = 1.5``: ``|mu| = 1.07e3``
at ``v_s = 0.142``, the largest ``Vr`` still -0.02 m/s short of the stick onset).
`walk` then hands the branch over to `MultipleCycleProblem`: the same cycle in
`SEGMENTS` segments (`beltmdsm.periodic.cycle_segments`), each amplifying by about
``|mu|^(1/m)``, on the same driver with the same hooks (the stick onset crossed by
`beltmdsm.cycles.stick`). Its own limit: a segment whose monodromy's norm passes
`MULTIPLIER_LIMIT` has single shooting's trouble again.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..continuation.driver import walk as drive
from ..continuation.problem import Residual, Step, failed
from ..continuation.settings import ContinuationSettings
from ..errors import NoPeriodicResponse
from ..periodic.cycle_segments import (
    continuity,
    segment_images,
    segment_jacobian,
    split_run,
    whole,
)
from ..periodic.newton import NEWTON_TOL
from .continuation import _SECTION_TOL, MULTIPLIER_LIMIT, CycleProblem

__all__ = ["MultipleCycleProblem", "SEGMENTS", "walk"]

#: Segments of a multiple-shooting cycle: at the hand-over (``|mu| = 1e3``) each
#: amplifies by about ``1e3^(1/16) = 1.5``; a segment reaches `MULTIPLIER_LIMIT` only
#: where the whole period's largest multiplier is of order ``1e48``.
SEGMENTS = 16
#: Back to single shooting where the largest multiplier falls below this (a tenth of
#: `MULTIPLIER_LIMIT`: no hand-over back and forth at one cycle): the stick-slip cycles
#: beyond the onset have a multiplier 0 and small ones, and single shooting is m times
#: cheaper.
HAND_BACK = MULTIPLIER_LIMIT / 10
#: Hand-overs on one walk at most.
MAX_HANDOVERS = 6
#: Secant iterations per cycle of a given largest ``Vr``.
GRAZING_ITER = 16
#: Halvings of a secant step whose cycle Newton's method does not reach.
GRAZING_HALVINGS = 6
#: The largest ``|max Vr|`` [m/s] of the sliding cycles extrapolated to the grazing one.
GRAZING_VR = 1e-4
#: How closely the secant method meets ``max Vr = -d`` [m/s]: the largest ``Vr`` is
#: read off a run over the period from ``x_0``, which amplifies its error (1e-12) by
#: up to ``|mu|`` (5e4 near the onset): 1e-10 leaves a margin above that.
GRAZING_VR_TOL = 1e-10
HANDED_BACK = "handed back to single shooting"


class MultipleCycleProblem(CycleProblem):
    """A self-excited cycle in ``m`` segments, continued in ``z = (x_0 / sx, ..,
    x_{m-1} / sx, T / sT, p / sp)`` (module docstring).

    Takes a `CycleProblem`'s flow, range and scales; its points are `CyclePoint`s whose
    ``segments`` hold the states at ``t = i T / m``. The Step data and ``correct``
    keep the single-shooting form ``(x_0, T, p, image)``, the image a
    `beltmdsm.periodic.cycle_segments.SegmentImages`, so that the stick-onset tools
    work on either problem.
    """

    def __init__(self, single: CycleProblem, m: int = SEGMENTS):
        self.__dict__.update(single.__dict__)
        self.m = int(m)
        self._states: dict[bytes, NDArray[np.float64]] = {}

    # -- unknowns

    def unpack_all(self, z):
        m = self.m
        return (
            z[: 4 * m].reshape(m, 4) * self.sx,
            float(z[4 * m] * self.sT),
            float(z[4 * m + 1] * self.sp),
        )

    def unpack(self, z):
        states, T, p = self.unpack_all(z)
        return states[0], T, p

    def states_of(self, x, T, p) -> NDArray[np.float64]:
        """The segments' starts of a cycle through ``x`` (those of the last solution
        there, else split from one run)."""
        x = np.asarray(x, float)
        if x.ndim == 2:
            return x
        known = self._states.get(x.tobytes())
        return known if known is not None else split_run(self.flow, x, T, p, self.m)

    def z_of(self, x, T, p) -> NDArray[np.float64]:
        states = self.states_of(x, T, p)
        return np.concatenate([states.ravel() / self.sx, [T / self.sT, p / self.sp]])

    def z(self, point) -> NDArray[np.float64]:
        states = point.segments if point.segments is not None else point.state
        return self.z_of(states, point.period, point.value)

    # -- equations

    def residual(self, z, extra, iteration) -> Residual:
        states, T, p = self.unpack_all(z)
        images = segment_images(self.flow, states, T, p)
        G = continuity(states, images) / self.sx
        H = self.flow.section(states[0], p) / self.hs
        size = max(float(np.max(np.abs(G))), abs(H), abs(extra))
        converged = (
            size * self.sx <= NEWTON_TOL * (1.0 + float(np.max(np.abs(states))))
            and abs(H) <= _SECTION_TOL
            and iteration > 1
        )
        return Residual(np.append(G.ravel(), H), size, converged, (states, T, p, images))

    def jacobian(self, *args, column=None) -> NDArray[np.float64]:  # type: ignore[override]
        """``d(G, H)/dz`` (4m+1 x 4m+2) at an evaluation ``(states, T, p, images)`` or
        at ``(x_0, T, p, SegmentImages)``; ``column``: the scaled ``p`` column."""
        if len(args) <= 2:
            data, column = args[0], args[1] if len(args) == 2 else column
        else:
            data, column = args[:4], args[4] if len(args) == 5 else column
        states, T, p, images = data
        if np.ndim(states) == 1 and hasattr(images, "segments"):  # (x_0, T, p, SegmentImages)
            states, images = images.states, images.segments
        elif np.ndim(states) == 1:  # a run from x_0 alone (beltmdsm.cycles.stick)
            states = split_run(self.flow, states, T, p, self.m)
            images = segment_images(self.flow, states, T, p)
        J = segment_jacobian(self.flow, states, T, p, images, column=column is None)
        # scaled: G / sx and H / hs in z = (x / sx, T / sT, p / sp)
        n = 4 * self.m
        J[:n, n] *= self.sT / self.sx
        J[n, :n] *= self.sx / self.hs
        if column is None:
            c = J[:, -1]
            column = np.append(c[:n] * self.sp / self.sx, c[n] * self.sp / self.hs)
        J[:, -1] = column
        return J

    def solution(self, data, iteration) -> Step:
        states, T, p, images = data
        self._states = {states[0].tobytes(): states}
        img = whole(self.flow, states, T, p, images)
        J = self.jacobian(data)
        return Step(self.z_of(states, T, p), p, J, iteration, (states[0], T, p, img))

    def point_at(self, x, T, p, img, tangent_p, J=None):
        point = super().point_at(x, T, p, img, tangent_p, J)
        point.segments = np.array(img.states)
        return point

    # -- the stick onset solved as the grazing cycle

    def rescue(self, points, prev, tangent, ds):
        """`CycleProblem.rescue`, the onset then solved from the sliding side
        (`grazing`): the extrapolation of `beltmdsm.cycles.stick.locate` stays about
        1e-4 off on these cycles (its trial points fall on both sides of a nonsmooth
        fold)."""
        crossed = super().rescue(points, prev, tangent, ds)
        if crossed is None or crossed[1][0].n_sticks:
            return crossed
        sliding = [q for q in points if q.n_sticks == 0]
        solved = self.grazing(sliding[-2:] + [crossed[1][0]])
        if solved is not None:
            crossed[0].value, crossed[0].accuracy = solved
        return crossed

    def grazing(self, sliding):
        """``(p, accuracy)`` of the grazing cycle (largest ``Vr = 0``) beyond the
        sliding cycles ``sliding`` (the last two or more of the branch), or None.

        ``max Vr = 0`` holds on every stick-slip cycle too (``X1' = Vb`` while stuck),
        and beyond a nonsmooth fold those lie next to the sliding ones, so the grazing
        cycle is not solved for itself: the sliding cycles with ``max Vr = -d`` for
        three ``d`` are, by the secant method in ``p`` on cycles corrected at ``p``
        fixed (`_pinned`), and their ``p``, smooth in ``d`` on the sliding side, is
        extrapolated to ``d = 0`` by a quadratic; the accuracy is its difference from
        the line through the nearest two.
        """
        if len(sliding) < 2:
            return None
        known = [(q.value, q.max_relative_velocity, self.z(q)) for q in sliding[-2:]]
        found = []
        for d in (GRAZING_VR, GRAZING_VR / 2, GRAZING_VR / 4):
            for _ in range(GRAZING_ITER):
                p1, v1, z1 = known[-1]
                if abs(v1 + d) <= GRAZING_VR_TOL:
                    break
                # the secant through a cycle far enough for its slope to stand above
                # the noise of max Vr (1e-10 over 1e-6 of p)
                far = [k for k in known[:-1] if abs(k[0] - p1) >= 1e-6 * max(1.0, abs(p1))]
                if not far:
                    return None
                p0, v0, z0 = far[-1]
                if v1 == v0 or p1 == p0:
                    return None
                step = (-d - v1) * (p1 - p0) / (v1 - v0)
                p2 = p1 + float(np.clip(step, -2 * abs(p1 - p0), 2 * abs(p1 - p0)))
                for _ in range(GRAZING_HALVINGS):
                    # predicted along the secant; where Newton's method fails from
                    # there (far from the onset, the cycle changes fast), half as far
                    got = self._pinned(z1 + (p2 - p1) / (p1 - p0) * (z1 - z0), p2)
                    if got is not None:
                        break
                    p2 = p1 + 0.5 * (p2 - p1)
                else:
                    return None
                known.append((p2, got[1], got[0]))
            else:
                return None
            found.append((d, known[-1][0]))
        d, p = np.array(found).T
        value = float(np.polyval(np.polyfit(d, p, 2), 0.0))
        accuracy = abs(value - float(np.polyval(np.polyfit(d[1:], p[1:], 1), 0.0)))
        return value, accuracy

    def _pinned(self, z, p):
        """``(z, max Vr)`` of the sliding cycle at ``p`` fixed, Newton's method from
        ``z``; None where it fails or the cycle sticks."""
        z = np.array(z, float)
        z[-1] = p / self.sp
        row = np.zeros(z.size)
        row[-1] = 1.0
        try:
            step = self.solve(z, lambda q: (float(q[-1] - z[-1]), row))
        except NoPeriodicResponse:
            return None
        x, T, p, img = step.data
        if any(int(new) == 0 for *_, new in img.run.events):
            return None
        if np.ptp(img.states[:, 1]) <= 1e-6 * (1.0 + abs(self.flow.at(p)[0]["Vb"])):
            return None  # steady sliding: a solution of the segments' equations too
        return step.z, self.flow.largest_vr(x, T, p)

    # -- its limits

    def stop(self, new):
        if new.max_abs_multiplier < HAND_BACK:
            return failed(new, HANDED_BACK)
        worst = max(float(np.linalg.norm(s.monodromy, 2)) for s in new.image.segments)
        if worst > MULTIPLIER_LIMIT:
            return failed(
                new,
                f"a segment of the {self.m} of multiple shooting amplifies by {worst:.3g} "
                f"(the cycle's largest multiplier {new.max_abs_multiplier:.3g}): the "
                "corrector's steps shrink towards nothing there, as single shooting's did",
            )
        return self.period_stop(new)


def _restart(problem, last, direction):
    """``(first point, tangent)`` of ``problem`` at the cycle ``last`` (corrected there
    with the parameter pinned), the tangent along ``direction`` in the components
    ``(x_0, T, p)`` that both shootings share; None where the corrector fails."""
    z = problem.z(last)
    row = np.zeros(z.size)
    row[-1] = 1.0
    try:
        step = problem.solve(z, lambda q: (float(q[-1] - z[-1]), row), fresh=True)
    except NoPeriodicResponse:
        return None
    t = problem.tangent(step.J)
    t = t if float(np.concatenate([t[:4], t[-2:]]) @ direction) >= 0 else -t
    first = problem.point(step, float(t[-1]))
    first.column = step.J[:, -1].copy()
    return first, t


def walk(cont, first, tangent, period0, settings: ContinuationSettings | None = None):
    """`beltmdsm.cycles.continuation.walk`, on multiple shooting while the largest
    multiplier lies above `MULTIPLIER_LIMIT` (handed back below `HAND_BACK`).

    Returns ``(points, special)`` as that walk; a hand-over is no special point (the
    branch goes on); the points solved by multiple shooting have ``segments``.
    """
    cont.period0 = period0
    ms = MultipleCycleProblem(cont)
    problem, points, special = cont, [first], []
    for _ in range(MAX_HANDOVERS + 1):
        more, found = drive(problem, points[-1], tangent, settings)
        points += more[1:]
        special += found
        end, last = special[-1], points[-1]
        if problem is cont:
            go_on = end.kind == "failed" and last.max_abs_multiplier > MULTIPLIER_LIMIT
        else:
            go_on = end.kind == "failed" and end.detail == HANDED_BACK
        if not go_on or len(points) < 2:
            break
        nxt = ms if problem is cont else cont
        direction = _shared(cont, last) - _shared(cont, points[-2])
        restarted = _restart(nxt, last, direction / np.linalg.norm(direction))
        if restarted is None:
            break
        special.pop()
        (points[-1], tangent), problem = restarted, nxt
    if special and special[-1].detail == HANDED_BACK:
        special[-1].detail = "single shooting fails on this cycle again"
    return points, special


def _shared(cont, point):
    """``(x_0 / sx, T / sT, p / sp)`` of a point of either shooting."""
    return cont.z_of(point.state, point.period, point.value)
