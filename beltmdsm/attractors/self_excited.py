"""The attractors of the autonomous model and the regions of the plane each one claims.

Without excitation (`beltmdsm.excitation.is_autonomous`) the invariant sets of Eq. (4)
are steady sliding (the unforced equilibrium, Eq. 9) and the self-excited cycles
(`beltmdsm.cycles`). The normal motion ``(X2, X2')`` does not depend on the tangential
state and sits at its equilibrium on every one of them, so a start with the normal
state at its equilibrium moves in the plane ``(X1, X1')``, where every cycle is a
closed curve around steady sliding. `landscape` computes the sets at one parameter
value: the equilibrium and its eigenvalues, and the cycles near the branch's points
(`beltmdsm.cycles.branch.cycle_branch`, corrected by `beltmdsm.periodic.cycle.cycle`) or
given, each sampled over one period (`ORBIT_SAMPLES`).

A start is decided as soon as it provably lands (`Landscape.decide`, `Landscape.land`):

* **By region.** The cycles, nested around the equilibrium, cut the plane into
  rings. A ring is invariant (a trajectory cannot cross a cycle in the plane), and by
  Poincare-Bendixson a bounded trajectory in it ends on one of its boundaries; a ring
  whose boundaries hold exactly one attractor (the unstable cycle between steady
  sliding and the stick-slip cycle, say) belongs to it. The outermost region goes to
  the outermost cycle where it is stable. Starts within `BAND` of a cycle are not
  decided by region (the sampled curve's error): they are run.
* **By stick.** A stick phase ends at one state (`beltmdsm.starts.cycle_seed.stick_end`,
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

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import NoPeriodicResponse
from ..excitation import initial_state
from ..integrate.events import integrate_events
from ..model import Model
from ..settings import SolverSettings
from .invariant_sets import (
    BAND,
    NORMAL_TOL,
    T_MAX,
    InvariantSet,
    Landscape,
    _inside,
    _polygon_area,
    _segment_distance,
)

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
#: The backward runs of `backward_seed`: their starts' offsets from steady sliding (in
#: ``X1'``, times ``Vb``) and their length in periods of steady sliding's pair.
BACKWARD_OFFSETS = (0.5, 0.25, 0.1, 0.03)
BACKWARD_PERIODS = 12
#: Radii x angles of the points of a focus ellipse where the field is checked.
FOCUS_GRID = (40, 128)
#: Every this many points of an orbit are checked to lie inside the next cycle.
_NEST_STRIDE = 400


def backward_seed(model: Model, eq: InvariantSet) -> list[tuple[NDArray[np.float64], float]]:
    """A guess ``[(state, period)]`` of the unstable pure-slip cycle around a stable
    steady sliding (``[]`` where none is found): backwards in time the focus repels
    and that cycle attracts, so a backward run of steady sliding's slip mode (the
    generated field, smooth there) from inside it settles on it. Runs from ``X1'``
    offsets of `BACKWARD_OFFSETS` times ``Vb``, largest first; a run that leaves the
    slip mode (it started outside the cycle, or there is none) or does not settle is
    dropped. Its last extremum of ``X1'`` and the time between two is the guess
    `beltmdsm.periodic.cycle.cycle` corrects.

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

    from ..starts.cycle_seed import section_direction

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

    from ..starts.cycle_seed import section_direction

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
        Cycles to correct (`beltmdsm.periodic.cycle.cycle`): the points of a branch at
        or near the model's value (`cycles_near`). Those that do not converge are left
        out.
    seed : bool
        Also the cycles seeded by a backward run from stable steady sliding
        (`backward_seed`: the unstable cycle around it) and from the stick end or
        unstable sliding (`beltmdsm.starts.cycle_seed.seed_cycle`).

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
    beltmdsm.periodic.cycle.cycle : corrects each.

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
    from ..periodic.cycle import cycle
    from ..starts.cycle_seed import require_autonomous, stick_end

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
