"""The attractors of the autonomous model and the regions of the plane each one claims.

Without excitation (`beltmdsm.excitation.is_autonomous`) the invariant sets of Eq. (4)
are steady sliding (the unforced equilibrium, Eq. 9) and the self-excited cycles
(`beltmdsm.cycles`). The normal motion ``(X2, X2')`` does not depend on the tangential
state and sits at its equilibrium on every one of them, so a start with the normal
state at its equilibrium moves in the plane ``(X1, X1')``, where every cycle is a
closed curve around steady sliding. `landscape` computes the sets at one parameter
value: the equilibrium and its eigenvalues, and the cycles near the branch's points
(`beltmdsm.cycles.branch.cycle_branch`, corrected by `beltmdsm.cycles.cycle.cycle`) or
given, each sampled over one period (`ORBIT_SAMPLES`).

A start is decided as soon as it provably lands (`Landscape.decide`, `Landscape.land`):

* **By region.** The cycles, nested around the equilibrium, cut the plane into
  rings. A ring is invariant (a trajectory cannot cross a cycle in the plane), and by
  Poincare-Bendixson a bounded trajectory in it ends on one of its boundaries; a ring
  whose boundaries hold exactly one attractor (the unstable cycle between steady
  sliding and the stick-slip cycle, say) belongs to it. The outermost region goes to
  the outermost cycle where it is stable. Starts within `BAND` of a cycle are not
  decided by region (the sampled curve's error): they are run.
* **By stick.** A stick phase ends at one state (`beltmdsm.cycles.seed.stick_end`,
  normal motion at its equilibrium): every start that sticks goes on from there, so
  its fate is that state's, computed once. This is exact: a stick-slip cycle passes
  through that state.
* **By the linearised focus.** Where steady sliding is stable, a quadratic Lyapunov
  function of its tangential Jacobian ``A`` (``A^T P + P A = -I``) has sublevel
  ellipses ``(x - x_eq)^T P (x - x_eq) < c``; the largest ``c`` (of a ladder) whose
  ellipse stays in the slip mode of steady sliding and on which the field decreases
  the function (checked on `FOCUS_GRID` points of the ellipse, the generated field) is
  steady sliding's. It decides the starts where no cycle bounds steady sliding's
  basin (past the stick onset, say).
* Otherwise the start is run (`beltmdsm.integrate.events`, exact switching) in chunks
  until one of the two applies to a state on its way, or `T_MAX` (undecided, -1).

The region rule rests on two facts stated here: the plane is invariant (the normal
state at its equilibrium; a start off it is run until the normal motion has settled
to `NORMAL_TOL`) and the cycles given are all the cycles at this value (those of the
branch through the Hopf point and of the seed from the stick end; an isolated branch
that neither reaches would be missed, and a ring with two stable or two unstable
boundaries is then left to the runs, not guessed).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.spatial import cKDTree

from ..errors import NoPeriodicResponse, StepTooSmall
from ..excitation import initial_state
from ..integrate.events import integrate_events
from ..integrate.switching import Mode
from ..model import Model
from ..settings import SolverSettings

__all__ = [
    "InvariantSet",
    "Landscape",
    "landscape",
    "BAND",
    "ORBIT_SAMPLES",
    "T_MAX",
    "NORMAL_TOL",
]

#: Samples of a cycle's orbit over one period (the curve the regions are cut by).
ORBIT_SAMPLES = 8000
#: Starts this close to a cycle's sampled curve (relative to ``1 + |x|``) are run,
#: not decided by region: the chord error of `ORBIT_SAMPLES` on these orbits is below
#: 1e-6, the cycle's own error (Newton's residual) below 1e-9.
BAND = 1e-5
#: Longest run of a start [s] (the peers' horizon, pyBasin's t = 500).
T_MAX = 500.0
#: The normal state is at its equilibrium within this (relative) for the plane's rules:
#: above the runs' own drift of it (their tolerance, `RTOL`).
NORMAL_TOL = 1e-6
#: Tolerances of the runs (the period maps' are 1e-10; a decision needs less).
RTOL, ATOL = 1e-8, 1e-10
#: The backward runs of `backward_seed`: their starts' offsets from steady sliding (in
#: ``X1'``, times ``Vb``) and their length in periods of steady sliding's pair.
BACKWARD_OFFSETS = (0.5, 0.25, 0.1, 0.03)
BACKWARD_PERIODS = 12
#: Radii x angles of the points of a focus ellipse where the field is checked.
FOCUS_GRID = (40, 128)
#: Every this many points of an orbit are checked to lie inside the next cycle.
_NEST_STRIDE = 400
#: States checked per chunk of a run (one chunk: the period of the equilibrium's pair).
_CHECKS = 32


@dataclass
class InvariantSet:
    """An equilibrium or a cycle of the autonomous model.

    Attributes
    ----------
    kind : {"equilibrium", "cycle"}
    stable : bool
    state : ndarray (4,)
        The equilibrium, or the cycle's state on its section.
    period : float or None
        The cycle's period [s].
    n_sticks : int
        Stick phases per period (0: pure slip).
    orbit : ndarray (m, 4)
        One period sampled (the equilibrium: its state).
    leading : float
        The largest real part of the eigenvalues (equilibrium) or the largest
        ``|multiplier|`` but the trivial one (cycle).

    See Also
    --------
    landscape : computes them.

    Examples
    --------
    >>> s = InvariantSet("equilibrium", True, np.zeros(4), None, 0, np.zeros((1, 4)), -0.1)
    >>> s
    InvariantSet(stable equilibrium)
    """

    kind: str
    stable: bool
    state: NDArray[np.float64] = field(repr=False)
    period: float | None
    n_sticks: int
    orbit: NDArray[np.float64] = field(repr=False)
    leading: float = field(repr=False)

    def __repr__(self) -> str:
        what = "stable" if self.stable else "unstable"
        if self.kind == "equilibrium":
            return f"InvariantSet({what} equilibrium)"
        slip = "stick-slip" if self.n_sticks else "pure-slip"
        return f"InvariantSet({what} {slip} cycle, period {self.period:.6g} s)"

    @property
    def name(self) -> str:
        """``steady sliding``, ``stick-slip cycle`` or ``pure-slip cycle``."""
        if self.kind == "equilibrium":
            return "steady sliding"
        return "stick-slip cycle" if self.n_sticks else "pure-slip cycle"


def backward_seed(model: Model, eq: InvariantSet) -> list[tuple[NDArray[np.float64], float]]:
    """A guess ``[(state, period)]`` of the unstable pure-slip cycle around a stable
    steady sliding (``[]`` where none is found): backwards in time the focus repels
    and that cycle attracts, so a backward run of steady sliding's slip mode (the
    generated field, smooth there) from inside it settles on it. Runs from ``X1'``
    offsets of `BACKWARD_OFFSETS` times ``Vb``, largest first; a run that leaves the
    slip mode (it started outside the cycle, or there is none) or does not settle is
    dropped. Its last extremum of ``X1'`` and the time between two is the guess
    `beltmdsm.cycles.cycle.cycle` corrects.

    Parameters
    ----------
    model : Model
    eq : InvariantSet
        Steady sliding.

    Returns
    -------
    list of (ndarray (4,), float)

    See Also
    --------
    landscape

    Examples
    --------
    >>> from beltmdsm import Model
    >>> m = Model(alpha=0.0, omega1=1.0, beta1=0.05, g=1.0, friction="stribeck",
    ...           mu_s=1.0, mu_k=0.5, v_s=0.5, Vb=1.5)
    >>> [(state, period)] = backward_seed(m, _equilibrium(m))
    >>> round(period, 1), bool(abs(state[1] + 1.252) < 0.05)  # the cycle: 6.295 s, X1' >= -1.252
    (6.3, True)
    """
    from scipy.integrate import solve_ivp

    from beltmdsm.generated import hybrid

    from ..cycles.seed import section_direction

    if not eq.stable:
        return []
    mode = section_direction(model)
    kernel = hybrid.bind_vector_field(**model.arguments(hybrid.bind_vector_field))
    vb = float(model["Vb"])
    lam = np.linalg.eigvals(_jacobian(model)[:2, :2])
    period = 2 * np.pi / max(float(np.max(np.abs(lam.imag))), 1e-12)

    x2, y2 = eq.state[2:]

    def field(t, y):  # the plane only: backwards the damped normal motion would blow up
        return kernel(0.0, y[0], y[1], x2, y2, mode)[:2]

    def leaves(t, y):  # V_r reaches 0: the slip mode ends
        return y[1] - vb

    leaves.terminal = True
    for share in BACKWARD_OFFSETS:
        y0 = eq.state[:2].copy()
        y0[1] -= share * vb
        span = BACKWARD_PERIODS * period
        sol = solve_ivp(field, (0.0, -span), y0, events=leaves, rtol=1e-7, atol=1e-9,
                        dense_output=True)  # fmt: skip
        if sol.status != 0:
            continue
        ts = np.linspace(-span + 3 * period, -span, 4000)
        v = sol.sol(ts)[1]
        low = [i for i in range(1, len(v) - 1) if v[i] <= v[i - 1] and v[i] <= v[i + 1]]
        if len(low) < 2:
            continue
        amplitude = float(np.ptp(v))
        if amplitude < 1e-6 * (1.0 + abs(vb)):
            continue  # decayed onto steady sliding: no cycle from here
        i, j = low[-2], low[-1]
        return [(np.array([*sol.sol(ts[j]), x2, y2]), float(abs(ts[j] - ts[i])))]
    return []


def _polygon_area(xy):
    x, y = xy[:, 0], xy[:, 1]
    return 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))


def _inside(xy, curve):
    """Whether each point of ``xy`` lies inside the closed polygon ``curve``."""
    from matplotlib.path import Path

    return Path(curve, closed=False).contains_points(xy)


def _segment_distance(xy, curve, tree):
    """The distance of each point from the closed polyline ``curve``: to the two
    segments at its nearest vertex (exact wherever the spacing is below the distance
    to every other part of the curve)."""
    _, i = tree.query(xy)
    n = len(curve)
    out = np.full(len(xy), np.inf)
    for a, b in ((i - 1) % n, i), (i, (i + 1) % n):
        p, q = curve[a], curve[b]
        d = q - p
        t = np.clip(np.sum((xy - p) * d, axis=1) / np.maximum(np.sum(d * d, axis=1), 1e-300), 0, 1)
        out = np.minimum(out, np.linalg.norm(xy - p - t[:, None] * d, axis=1))
    return out


def _polar(curve, centre):
    """``(theta, r, sine)`` of a closed curve seen from ``centre`` where every ray from
    it meets the curve once (its angle turns one way), sorted by angle; ``sine`` the
    least sine of the angle between the curve and a ray (a radial distance ``d`` is a
    distance of at least ``d * sine``). None for a curve that is not star-shaped."""
    d = curve - centre
    theta = np.arctan2(d[:, 1], d[:, 0])
    turn = np.diff(np.unwrap(np.append(theta, theta[0])))
    if not (np.all(turn > 0) or np.all(turn < 0)):
        return None
    r = np.hypot(d[:, 0], d[:, 1])
    chord = np.roll(curve, -1, axis=0) - curve
    cross = np.abs(d[:, 0] * chord[:, 1] - d[:, 1] * chord[:, 0])
    sine = float(np.min(cross / np.maximum(r * np.hypot(chord[:, 0], chord[:, 1]), 1e-300)))
    order = np.argsort(theta)
    return theta[order], r[order], sine


@dataclass
class Landscape:
    """The invariant sets of an autonomous model at one parameter value and the rules
    that decide a start (module docstring).

    Attributes
    ----------
    model : Model
    equilibrium : InvariantSet
    cycles : list of InvariantSet
        By enclosed area, smallest first.
    attractors : list of InvariantSet
        The stable ones, in the order of the labels: steady sliding first, then the
        cycles from the inside out.
    nested : bool
        The cycles are nested around the equilibrium (the region rule holds).
    stick_end : ndarray (4,) or None
        Where every stick phase ends (`beltmdsm.cycles.seed.stick_end`).
    stick_label : int or None
        The label of the attractor the stick end lands on (None: undecided, or no
        stick end).

    See Also
    --------
    landscape : computes it.
    beltmdsm.studies.basin_stability.basin_stability : samples starts with it.
    """

    model: Model = field(repr=False)
    equilibrium: InvariantSet
    cycles: list[InvariantSet]
    attractors: list[InvariantSet] = field(repr=False)
    nested: bool = field(repr=False)
    stick_end: NDArray[np.float64] | None = field(repr=False)
    stick_label: int | None = field(repr=False, default=None)
    focus: tuple | None = field(repr=False, default=None)
    _trees: list = field(repr=False, default_factory=list)
    _polars: list = field(repr=False, default_factory=list)
    _rules: list = field(repr=False, default_factory=list)

    def __post_init__(self):
        self._derive()

    def _derive(self):
        self._trees = [cKDTree(c.orbit[:, :2]) for c in self.cycles]
        centre = self.equilibrium.state[:2]
        self._polars = [_polar(c.orbit[:, :2], centre) for c in self.cycles]
        self._rules = self._region_rules()

    def __getstate__(self):
        # sent to every task of an executor: the tables derived from the orbits are
        # rebuilt there (milliseconds) rather than shipped (half the bytes)
        return {k: v for k, v in self.__dict__.items() if k not in ("_trees", "_polars")}

    def __setstate__(self, state):
        self.__dict__.update(state)
        self._derive()

    def _near_inside(self, xy, i, band):
        """Within ``band`` of cycle ``i``, and inside it: by its polar table where it is
        star-shaped about the equilibrium (a start costs a bisection), else by the
        polygon and the distance to its segments."""
        polar = self._polars[i]
        if polar is None:
            curve = self.cycles[i].orbit[:, :2]
            near = _segment_distance(xy, curve, self._trees[i]) <= band
            return near, _inside(xy, curve)
        theta, r, sine = polar
        d = xy - self.equilibrium.state[:2]
        rc = np.interp(np.arctan2(d[:, 1], d[:, 0]), theta, r, period=2 * np.pi)
        gap = np.hypot(d[:, 0], d[:, 1]) - rc
        return np.abs(gap) * sine <= band, gap < 0

    def _label(self, s: InvariantSet) -> int:
        return next(i for i, a in enumerate(self.attractors) if a is s)

    def _region_rules(self):
        """The label of each ring from the inside out (None: not decided by region)."""
        if not self.nested or not self.cycles:
            return []
        rules = []
        bounds = [self.equilibrium, *self.cycles, None]
        for inner, outer in zip(bounds[:-1], bounds[1:]):
            stable = [s for s in (inner, outer) if s is not None and s.stable]
            rules.append(self._label(stable[0]) if len(stable) == 1 else None)
        return rules

    def decide(self, states: ArrayLike) -> NDArray[np.int_]:
        """The label each state is decided to land on by region alone, -1 where the
        region rule does not decide it (near a cycle, off the plane, or a ring without
        exactly one attracting boundary).

        Parameters
        ----------
        states : array_like (n, 4)

        Returns
        -------
        ndarray (n,) of int
        """
        y = np.atleast_2d(np.asarray(states, dtype=float))
        out = np.full(len(y), -1)
        eq = self.equilibrium.state
        planar = np.all(np.abs(y[:, 2:] - eq[2:]) <= NORMAL_TOL * (1.0 + np.abs(eq[2:])), axis=1)
        if not self._rules:
            return self._in_focus(y, planar, out)
        xy = y[:, :2]
        scale = 1.0 + np.max(np.abs(xy), axis=1)
        near = np.zeros(len(y), dtype=bool)
        ring = np.zeros(len(y), dtype=int)  # the cycles that do not contain it: 0 innermost
        for i in range(len(self.cycles)):
            close, inside = self._near_inside(xy, i, BAND * scale)
            near |= close
            ring += ~inside
        rules = np.array([-1 if r is None else r for r in self._rules])
        ok = planar & ~near
        out[ok] = rules[ring[ok]]
        return self._in_focus(y, planar, out)

    def _in_focus(self, y, planar, out):
        if self.focus is None:
            return out
        P, c = self.focus
        d = y[:, :2] - self.equilibrium.state[:2]
        inside = planar & (out < 0) & (np.einsum("ni,ij,nj->n", d, P, d) < c)
        out[inside] = self._label(self.equilibrium)
        return out

    def land(self, start: ArrayLike, t_max: float = T_MAX) -> dict[str, Any]:
        """Decide ``start``: by region at once, else by a run that stops as soon as a
        state on its way sticks or is decided by region (module docstring).

        Parameters
        ----------
        start : array_like (4,)
        t_max : float
            The longest run [s].

        Returns
        -------
        dict
            ``{"label", "how", "t"}``: the label (-1: undecided), ``"region"``,
            ``"stick"`` or ``"none"``, and the time run [s]. JSON-ready.
        """
        y = np.asarray(start, dtype=float)
        label = int(self.decide(y[None, :])[0])
        if label >= 0:
            return {"label": label, "how": "region", "t": 0.0}
        return self._run(y, t_max, self.stick_label)

    def _run(self, y, t_max, stick_label):
        chunk = _chunk_length(self)
        t = 0.0
        eq = self.equilibrium.state
        while t < t_max:
            span = min(chunk, t_max - t)
            settings = SolverSettings(
                t_end=t + span, rtol=RTOL, atol=ATOL, dt=span / 100, t_discard=0.0
            )
            try:
                run = integrate_events(self.model, settings, y0=y, t0=t)
            except StepTooSmall:
                return {"label": -1, "how": "none", "t": t}
            sticks = [
                e[0]
                for e in run.events
                if Mode(int(e[2])) == Mode.STICK
                and np.all(
                    np.abs(run.trajectory.state(np.array([e[0]]))[2:, 0] - eq[2:])
                    <= NORMAL_TOL * (1.0 + np.abs(eq[2:]))
                )
            ]
            end = run.trajectory.t_end
            if sticks and stick_label is not None:
                return {"label": int(stick_label), "how": "stick", "t": float(sticks[0])}
            ts = np.linspace(t, end, _CHECKS + 1)[1:]
            if sticks:
                ts = ts[ts < sticks[0]]
            labels = self.decide(run.trajectory.state(ts).T)
            hit = np.flatnonzero(labels >= 0)
            if hit.size:
                return {"label": int(labels[hit[0]]), "how": "region", "t": float(ts[hit[0]])}
            if run.status != "done":
                return {"label": -1, "how": "none", "t": float(end)}
            y, t = run.trajectory.state(np.array([end]))[:, 0], float(end)
        return {"label": -1, "how": "none", "t": t}


def _chunk_length(ls):
    period = [c.period for c in ls.cycles if c.period]
    return float(min(period)) if period else 2 * math.pi


def _jacobian(model):
    from beltmdsm.generated import unforced

    return np.asarray(
        unforced.jacobian_at_equilibrium(**model.arguments(unforced.jacobian_at_equilibrium)),
        dtype=float,
    ).reshape(4, 4)


def _equilibrium(model):
    state = initial_state(model)
    lead = float(np.max(np.linalg.eigvals(_jacobian(model)).real))
    return InvariantSet("equilibrium", lead < 0, state, None, 0, state[None, :], lead)


def _focus(model, eq):
    """``(P, c)``: the largest sublevel ellipse of steady sliding's quadratic Lyapunov
    function that stays in its slip mode and on whose `FOCUS_GRID` points the field
    decreases it (module docstring); None where none of the ladder does."""
    from scipy.linalg import solve_continuous_lyapunov

    from beltmdsm.generated import hybrid

    from ..cycles.seed import section_direction

    A = _jacobian(model)[:2, :2]
    P = solve_continuous_lyapunov(A.T, -np.eye(2))
    Q = np.linalg.inv(P)
    vb = abs(float(model["Vb"])) - abs(float(eq.state[1]))
    c = 0.9 * vb**2 / Q[1, 1]  # the ellipse's reach in X1' is sqrt(c Q_11)
    L = np.linalg.cholesky(Q)
    radii, angles = FOCUS_GRID
    r = np.linspace(1.0 / radii, 1.0, radii)[:, None]
    a = np.linspace(0.0, 2 * np.pi, angles, endpoint=False)[None, :]
    unit = np.stack([(r * np.cos(a)).ravel(), (r * np.sin(a)).ravel()])
    mode = section_direction(model)  # the slip mode of steady sliding
    args = model.arguments(hybrid.vector_field)
    for _ in range(30):
        d = np.sqrt(c) * (L @ unit)
        x1, y1 = eq.state[0] + d[0], eq.state[1] + d[1]
        n = np.ones_like(x1)
        f = hybrid.vector_field(0.0, x1, y1, eq.state[2] * n, eq.state[3] * n, mode, **args)
        f = np.asarray(f, dtype=float).reshape(len(x1), 4).T[:2]  # rows: one state each
        if np.all(np.einsum("in,ij,jn->n", d, P, f) < 0):
            return P, c
        c *= 0.5
    return None


def _orbit(model, c):
    settings = SolverSettings(
        t_end=c.period, rtol=1e-10, atol=1e-12, dt=c.period / 100, t_discard=0.0
    )
    run = integrate_events(model, settings, y0=c.state)
    ts = np.linspace(0.0, c.period, ORBIT_SAMPLES, endpoint=False)
    return run.trajectory.state(ts).T


def _as_set(model, c):
    lead = float(np.max(np.abs(c.multipliers))) if len(c.multipliers) else 0.0
    stable = bool(c.stable) if c.stable is not None else False
    return InvariantSet(
        "cycle", stable, np.asarray(c.state), float(c.period), int(c.n_sticks),
        _orbit(model, c), lead,
    )  # fmt: skip


def _distinct(sets, new):
    for s in sets:
        if abs(s.period - new.period) <= 1e-6 * s.period:
            d = np.min(np.max(np.abs(s.orbit[:, :2] - new.state[:2]), axis=1))
            if d <= 1e-5 * (1.0 + np.max(np.abs(new.state[:2]))):
                return False
    return True


def landscape(
    model: Model,
    *,
    guesses: list[tuple[ArrayLike, float]] | None = None,
    seed: bool = True,
) -> Landscape:
    """The equilibrium and the cycles of the autonomous ``model``, and the rules that
    decide a start (module docstring).

    Parameters
    ----------
    model : Model
        Without excitation.
    guesses : list of (state, period), optional
        Cycles to correct (`beltmdsm.cycles.cycle.cycle`): the points of a branch at
        or near the model's value (`cycles_near`). Those that do not converge are left
        out.
    seed : bool
        Also the cycles seeded by a backward run from stable steady sliding
        (`backward_seed`: the unstable cycle around it) and from the stick end or
        unstable sliding (`beltmdsm.cycles.seed.seed_cycle`).

    Returns
    -------
    Landscape

    Raises
    ------
    ValueError
        For a model with excitation.

    See Also
    --------
    cycles_near : the guesses from a branch.
    beltmdsm.cycles.cycle.cycle : corrects each.

    Examples
    --------
    The friction oscillator of bSTAB and pyBasin at ``Vb = 1.5``: steady sliding is
    stable, inside an unstable pure-slip cycle, itself inside the stable stick-slip
    cycle; a start near steady sliding is its, one near the belt's speed the cycle's:

    >>> from beltmdsm import Model
    >>> m = Model(alpha=0.0, omega1=1.0, beta1=0.05, g=1.0, friction="stribeck",
    ...           mu_s=1.0, mu_k=0.5, v_s=0.5, Vb=1.5)
    >>> ls = landscape(m)
    >>> ls.equilibrium, ls.cycles  # doctest: +NORMALIZE_WHITESPACE
    (InvariantSet(stable equilibrium), [InvariantSet(unstable pure-slip cycle,
    period 6.29533 s), InvariantSet(stable stick-slip cycle, period 6.31631 s)])
    >>> normal = list(ls.equilibrium.state[2:])
    >>> ls.decide([[0.55, 0.5, *normal], [0.55, 1.9, *normal]]).tolist()
    [0, 1]
    """
    from ..cycles.cycle import cycle
    from ..cycles.seed import require_autonomous, stick_end

    require_autonomous(model, "basins without excitation")
    eq = _equilibrium(model)
    found = []
    tries = [(g, p) for g, p in (guesses or [])]
    if seed:
        tries += backward_seed(model, eq) + [(None, None)]
    for guess, period in tries:
        try:
            c = cycle(model, guess, period)
        except NoPeriodicResponse:
            continue
        if c.grazing if hasattr(c, "grazing") else False:
            continue
        s = _as_set(model, c)
        if _distinct(found, s):
            found.append(s)
    found.sort(key=lambda s: _polygon_area(s.orbit[:, :2]))
    # two periodic orbits of the plane never cross: a few points of one decide whether it
    # lies inside the other
    nested = all(bool(_inside(eq.state[None, :2], c.orbit[:, :2])[0]) for c in found) and all(
        bool(np.all(_inside(a.orbit[::_NEST_STRIDE, :2], b.orbit[:, :2])))
        for a, b in zip(found, found[1:])
    )
    attractors = [s for s in [eq, *found] if s.stable]
    focus = _focus(model, eq) if eq.stable else None
    ls = Landscape(model, eq, found, attractors, nested, stick_end(model), None, focus)
    if ls.stick_end is not None:
        ls.stick_label = _stick_label(ls)
    return ls


def _stick_label(ls):
    """The label of the attractor the stick end lands on: the stable stick-slip cycle
    that passes through it (exact), else the stick end's run."""
    xy = ls.stick_end[None, :2]
    for c, tree in zip(ls.cycles, ls._trees):
        d = _segment_distance(xy, c.orbit[:, :2], tree)[0]
        if c.stable and c.n_sticks and d <= BAND * (1.0 + float(np.max(np.abs(xy)))):
            return ls._label(c)
    label = ls._run(ls.stick_end, T_MAX, None)["label"]
    return None if label < 0 else label


def cycles_near(branch: Any, value: float) -> list[tuple[NDArray[np.float64], float]]:
    """Guesses ``(state, period)`` of the cycles of ``branch`` at ``value``: the point
    nearest to it on each stretch of the branch that passes it.

    Parameters
    ----------
    branch : beltmdsm.cycles.branch.CycleBranch
    value : float

    Returns
    -------
    list of (ndarray (4,), float)

    See Also
    --------
    landscape

    Examples
    --------
    >>> from types import SimpleNamespace as P
    >>> b = P(points=[P(value=v, state=np.full(4, v), period=6.0) for v in (1.0, 2.0, 1.5)])
    >>> [(float(x[0]), T) for x, T in cycles_near(b, 1.9)]
    [(2.0, 6.0), (2.0, 6.0)]
    """
    pts = branch.points
    out = []
    for a, b in zip(pts, pts[1:]):
        if (a.value - value) * (b.value - value) <= 0:
            p = a if abs(a.value - value) <= abs(b.value - value) else b
            out.append((np.array(p.state, dtype=float), float(p.period)))
    return out
