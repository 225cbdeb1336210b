"""Predicted unstable belt speeds: the paper's analysis and a consistent MDSM.

The paper (Sects. 4.2-4.3) linearises the slow equations with the slope ``mu_bar'`` of
Eq. (25); `beltmdsm.generated.stability` gives its unstable interval in closed form. The
consistent analysis here keeps what the paper drops (docs/modelling.md#averaging): the
correlation between the fast friction direction and the fast normal force.

Both follow the model's laws (``friction=``, ``contact=``; `Model.arguments` hands each
generated function the options it declares), and neither computes with another law's
physics. For a belt speed ``Vb`` the consistent MDSM

1. takes the fast normal force ``N(t) = g + N1 sin(Omega t + psi)`` from the linear
   normal response (`beltmdsm.generated.correlation.fast_normal_force`; the normal motion does
   not depend on the tangential one, the capability ``one_way_coupling``, checked);
2. finds the fast relative velocity ``V sin(Omega t + phi)`` by harmonic balance of the
   tangential equation (Eq. A1, `beltmdsm.generated.correlation.harmonic_balance`: the
   transfer function of the tangential oscillator, the excitation and the first
   harmonic of the law's friction force, `friction_harmonic`). Without a reversal of
   the friction within a fast cycle (``V <= Vb``) and a friction coefficient that is
   constant in slip (the capability ``slip_friction_state_independent``: Coulomb's
   law) the balance is linear and its solution the coupled ``V_hat``
   (`beltmdsm.generated.correlation.fast_tangential_velocity`); otherwise (a reversal, or a
   coefficient that varies with the sliding speed, Stribeck's) it is a two-unknown
   nonlinear system, solved by Newton iterations continued in ``Vb``;
3. linearises the averaged friction ``<mu(|v|) sgn(v) N>`` in the slow velocity at
   frozen fast amplitude and phase: the tangential damping is
   `beltmdsm.generated.correlation.slow_damping`, ``2 beta1 omega1 + d<...>/du`` (for
   Coulomb's law ``2 beta1 omega1 + mu_s dF/du``), unstable when negative (the normal
   block is that of Eq. 22 and always stable). For a law without a closed-form fast
   average (Stribeck's) the averages are quadratures of the same expression.

Only one excitation frequency is covered (``Omega_t == Omega_n``): with two frequencies
a single harmonic balance does not apply and `consistent_mdsm_damping` raises.

The paper's closed forms (Eqs. 25, 28) need the law's fast average in closed form (the
capability ``closed_form_average``) and a ``V_hat`` that does not depend on ``Vb``;
where either fails (Stribeck's law) `paper_intervals` finds the same analysis' unstable
set numerically (`paper_numeric`): the sign of the pointwise
`beltmdsm.generated.stability.growth_rate` (its effective friction a quadrature of the law's
expression) on a grid of ``Vb``, each edge refined by ``brentq``, with ``V_hat`` of the
chosen reading evaluated at each ``Vb`` (the fast amplitude frozen in the slow
linearisation: the slope is ``d mu_bar / d Vr`` at fixed ``V_hat``), and
`paper_reasons` says so with its grid and tolerance.

The tension law (`predict`'s ``tension=``, docs/modelling.md#tension): the paper's
analyses linearise at the equilibrium, where the contact force is ``g > 0``, so
their closed forms are the same under both laws. The consistent MDSM takes a
harmonic fast normal force ``g + N1 sin``; with ``tension="clipped"`` and
``N1 >= g`` the clip ``max(F, 0)`` cuts it off and it is no longer harmonic, so that
analysis gives no prediction (`CLIPPED_MDSM`) rather than the allowed law's.

A friction law with a static bound of its own (``static_kinetic``: stick held up to
``mu_s F``, slip at ``mu_k F``): every analysis here linearises sliding and averages the
slip law over a fast motion that passes ``Vr = 0`` without sticking, so it takes the
kinetic coefficient and the static bound enters none of them. Their verdicts are
local: where the static bound exceeds the kinetic coefficient a stick-slip cycle can
coexist with stable sliding, and `predict` says so in each analysis' note
(`STATIC_BOUND`).
"""

from __future__ import annotations

import math
import sys
from collections.abc import Mapping
from dataclasses import asdict, dataclass, field
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy import optimize

from beltmdsm.generated import _support, correlation, friction, stability, unforced
from beltmdsm.generated.parameters import STATIC_BOUNDS

from .. import intervals
from ..errors import Refused
from ..model import OPTION_DEFAULTS, Model, as_model, require
from ..settings import MAX_VB_POINTS

__all__ = [
    "FastMotion",
    "fast_motion",
    "consistent_mdsm_damping",
    "reversal_onset",
    "unstable_intervals",
    "paper_intervals",
    "paper_reasons",
    "paper_numeric",
    "PAPER_POINTS",
    "PAPER_XTOL",
    "PAPER_NUMERIC",
    "predict",
    "Prediction",
    "NO_EXCITATION",
    "NO_FAST_MOTION",
    "NO_VHAT",
    "NUMERIC_NO_AVERAGE",
    "NUMERIC_VHAT_OF_VB",
    "CLIPPED_MDSM",
    "CLIPPED_PAPER",
    "STATIC_BOUND",
    "clip_acts",
    "ONSET_STEP",
    "GRID_COARSE",
    "UNFORCED_NUMERIC",
    "UNFORCED_SCAN",
    "grid_note",
    "unforced_rate",
    "unforced_edges",
]


@dataclass(frozen=True)
class FastMotion:
    """Fast motion at one belt speed.

    ``v = V sin(Omega t + phi)``, ``N = g + N1 sin(Omega t + psi)``.

    ``reverses`` is True when the friction changes direction within a fast cycle
    (``V > Vb``); ``theta = psi - phi`` is the phase of the normal force ahead of the
    velocity; ``residual`` the relative residual of the harmonic balance.
    """

    V: float
    phi: float
    N1: float
    psi: float
    reverses: bool
    residual: float

    @property
    def theta(self) -> float:
        return self.psi - self.phi


def _single_frequency(p):
    if p["Omega_t"] != p["Omega_n"]:
        raise ValueError(
            "the harmonic balance needs one excitation frequency: "
            f"Omega_t = {p['Omega_t']} != Omega_n = {p['Omega_n']}"
        )
    return p["Omega_t"]


def _linear_without_reversal(model: Model) -> bool:
    """Whether the fast motion without a reversal of the friction is the linear response
    (`beltmdsm.generated.correlation.fast_tangential_velocity`, exact): where the slip friction
    does not depend on the tangential state (Coulomb's constant coefficient), it is a
    linear function of the normal force. Otherwise the harmonic balance is solved."""
    return model.fact("slip_friction_state_independent")[0]


class _Balance:
    """The harmonic balance of the fast tangential motion at one belt speed.

    ``residual((V, phi))`` is `beltmdsm.generated.correlation.harmonic_balance` (relative to the
    excitation's size) with the model's friction law and the fast normal force
    ``N1, psi`` (`beltmdsm.generated.correlation.fast_normal_force`).
    """

    def __init__(self, model: Model, N1: float, psi: float) -> None:
        if model["alpha_t"] == 0:
            raise ValueError(
                "alpha_t = 0: the residual of the harmonic balance "
                "(beltmdsm.generated.correlation.harmonic_balance) is relative to the tangential "
                "excitation alpha_t Omega_t^2, which is 0 here"
            )
        self.kw = model.arguments(correlation.harmonic_balance)
        self.N1, self.psi, self.Vb = N1, psi, model["Vb"]

    def residual(self, z):
        V, phi = z
        re, im = correlation.harmonic_balance(V, phi, self.N1, self.psi, **self.kw)
        return np.array([float(re), float(im)])

    def log(self, z):
        """In ``(log V, phi)``: every iterate keeps ``V > 0``."""
        return self.residual((np.exp(z[0]), z[1]))

    def reversing(self, z):
        """In ``(s, phi)`` with ``V = Vb + s^2``: every iterate reverses.

        At the onset of reversal (``V = Vb``) the first harmonic of the friction has a
        square-root singularity in ``V``: the reversal lasts a phase interval of width
        proportional to ``sqrt(V - Vb)``. In ``s`` it is smooth, so Newton's method
        converges next to the linear amplitude, where it stalls in ``V``.
        """
        return self.residual((self.Vb + z[0] ** 2, z[1]))

    def steady(self, z):
        """In ``(s, phi)`` with ``V = Vb (1 - s^2 / (1 + s^2))``: no iterate reverses and
        every one keeps ``0 < V <= Vb``."""
        return self.residual((self.Vb / (1 + z[0] ** 2), z[1]))


def _hybr(fun, start):
    """``scipy.optimize.root`` (hybr) from ``start``; None if an iterate had ``V <= 0``."""
    try:
        return optimize.root(fun, start, method="hybr", options={"xtol": 1e-13})
    except ValueError:
        # the generated harmonic_balance refuses V <= 0 (the parameters themselves are
        # checked when the model is built)
        return None


#: The shallowest reversal a solution of the harmonic balance may have, relative to
#: ``V``: ``V - Vb`` of 1024 ulps of ``V``. Below it the first harmonic of the friction
#: (``sqrt(1 - Vb^2 / V^2)``) carries a relative rounding error of about
#: ``eps V / (2 (V - Vb))``, over 5e-4, and a near-root at ``V -> Vb`` (no reversal)
#: can pass the residual test next to the linear amplitude.
_SHALLOWEST_REVERSAL = 1024 * np.finfo(float).eps
#: The largest residual of the harmonic balance (relative to the excitation) accepted.
_TOLERANCE = 1e-9


def _linear(model: Model) -> tuple[float, float]:
    """``(V, phi)`` of the linear fast response without reversal at the model's ``Vb``."""
    fn = correlation.fast_tangential_velocity
    V, phi = (float(x) for x in fn(**model.arguments(fn)))
    return V, phi


def _normal(model: Model) -> tuple[float, float]:
    fn = correlation.fast_normal_force
    N1, psi = (float(x) for x in fn(**model.arguments(fn)))
    return N1, psi


def _steady_motion(balance, start, N1, psi) -> FastMotion | None:
    """The solution without reversal (``V <= Vb``) of the harmonic balance from
    ``start = (V, phi)``, or None where Newton's method finds none."""
    Vb = balance.Vb
    V0 = min(start[0], Vb)
    s0 = math.sqrt(max(Vb / V0 - 1, 1e-6)) if V0 > 0 else 1.0
    sol = _hybr(balance.steady, (s0, start[1]))
    if sol is None:
        return None
    V = Vb / (1 + sol.x[0] ** 2)
    residual = float(np.max(np.abs(balance.residual((V, sol.x[1])))))
    if not residual <= _TOLERANCE:
        return None
    return FastMotion(V, float(np.angle(np.exp(1j * sol.x[1]))), N1, psi, False, residual)


def fast_motion(model: Model, guess: FastMotion | None = None) -> FastMotion:
    """The fast motion at the model's ``Vb``.

    Parameters
    ----------
    guess : FastMotion, optional
        Start of the Newton iterations (continuation from a neighbouring ``Vb``), whose
        kind (reversing or not) is tried first; default: the linear solution, and the
        solution without reversal first (the one Coulomb's law has wherever it exists).

    Raises
    ------
    RuntimeError
        If the harmonic balance does not converge.
    ValueError
        Two excitation frequencies, or laws whose normal motion depends on the
        tangential one (`beltmdsm.model.Unsupported`, naming the law).
    """
    p = model.params
    _single_frequency(p)
    require(model, "one_way_coupling", "the consistent MDSM's fast normal force")
    N1, psi = _normal(model)
    # Friction of constant direction (Vr < 0 throughout): the linear, coupled response
    # (for a coefficient that varies in slip its linearisation at Vb).
    V_lin, phi_lin = _linear(model)
    Vb = p["Vb"]
    if V_lin == 0:
        # no excitation reaches the tangential motion: no fast motion at all
        return FastMotion(0.0, phi_lin, N1, psi, False, 0.0)
    linear = _linear_without_reversal(model)
    if linear and V_lin <= Vb:
        return FastMotion(V_lin, phi_lin, N1, psi, False, 0.0)
    balance = _Balance(model, N1, psi)
    # without a guess the solution without reversal is preferred where it exists, as
    # for Coulomb's law (at the onset a reversing one coexists with it)
    steady_first = not linear and (guess is None or not guess.reverses)
    if steady_first:
        start = (guess.V, guess.phi) if guess is not None else (V_lin, phi_lin)
        found = _steady_motion(balance, start, N1, psi)
        if found is not None:
            return found
    reversing = guess is not None and guess.reverses
    start = (guess.V, guess.phi) if reversing else (V_lin, phi_lin)
    # The attempts, in order: Newton's method (hybr) in V, then in log V (where V is
    # small, Vb near 0 or an excitation at resonance, a step can cross V = 0; in log V
    # it cannot), then in s = sqrt(V - Vb) (`_Balance.reversing`; next to the linear
    # amplitude, where the first two stall on the square-root singularity), from the
    # guess and from reversals of 1 %, 10 % and 100 % of the linear amplitude (the
    # reversing solution there has V - Vb of the order of 1e-3 V_lin, and a start
    # below half of it falls towards s = 0, which is no solution). Tried in this
    # order, so that the cases the direct iteration solves keep their digits.
    attempts = [
        (balance.residual, start, lambda x: x),
        (balance.log, (math.log(start[0]), start[1]), math.exp),
    ]
    depths = [start[0] - Vb] if start[0] > Vb else []
    depths += [f * V_lin for f in (0.01, 0.1, 1.0)]
    attempts += [
        (balance.reversing, (math.sqrt(d), start[1]), lambda x: Vb + x * x) for d in depths
    ]
    residual, why = np.inf, ""
    for fun, z0, to_V in attempts:
        sol = _hybr(fun, z0)
        if sol is None:
            why = "an iterate reached V <= 0"
            continue
        V = float(to_V(sol.x[0]))
        if not V - Vb > _SHALLOWEST_REVERSAL * V:
            # the friction would not reverse, which holds only without a reversing
            # solution; or the reversal is too shallow for the first harmonic to be
            # told from rounding
            why = f"an iterate settled at V = {V!r}, without a resolved reversal (Vb = {Vb!r})"
            continue
        # hybr may report "not making good progress" once at machine precision: the
        # residual itself is the criterion.
        residual = float(np.max(np.abs(balance.residual((V, sol.x[1])))))
        why = sol.message
        if residual <= _TOLERANCE:
            phi = sol.x[1]
            return FastMotion(V, float(np.angle(np.exp(1j * phi))), N1, psi, True, residual)
    if not linear and not steady_first:
        found = _steady_motion(balance, (V_lin, phi_lin), N1, psi)
        if found is not None:
            return found
    raise RuntimeError(
        f"harmonic balance did not converge at Vb = {Vb}: {why} (residual {residual:.1e})"
    )


def consistent_mdsm_damping(model: Model, fast: FastMotion | None = None) -> float:
    """Tangential damping of the slow motion at ``-Vb``
    (`beltmdsm.generated.correlation.slow_damping`, with the model's friction law; for
    Coulomb's ``2 beta1 omega1 + mu_s dF/du``).

    Without fast motion (no excitation) it is the damping of the unforced equilibrium,
    ``-J[1, 1]`` of `beltmdsm.generated.unforced.jacobian_at_equilibrium` (for Coulomb's law
    ``2 beta1 omega1``: the average of friction of constant direction does not depend
    on the slow velocity).
    """
    fast = fast or fast_motion(model)
    if fast.V == 0:
        fn = unforced.jacobian_at_equilibrium
        return float(-fn(**model.arguments(fn))[1, 1])
    fn = correlation.slow_damping
    return float(fn(fast.V, fast.N1, fast.theta, **model.arguments(fn)))


def reversal_onset(model: Model, start: float | None = None) -> float:
    """The belt speed where the friction starts to reverse within a fast cycle.

    The fast motion without reversal just touches ``Vr = 0``: ``V(Vb) = Vb``. For a
    coefficient constant in slip (`_linear_without_reversal`) ``V`` does not depend on
    ``Vb`` and the onset is the linear amplitude in closed form; otherwise the
    harmonic balance at ``V = Vb`` is solved for ``(Vb, phi)``, from ``start`` (default:
    the linear amplitude at the linear amplitude). 0 without fast motion.

    Raises
    ------
    RuntimeError
        If the balance does not converge (naming the belt speed it started from).
    """
    V_lin, phi_lin = _linear(model if start is None else model.replace(Vb=start))
    if _linear_without_reversal(model) or V_lin == 0:
        return V_lin
    N1, psi = _normal(model)
    if start is None:
        V_lin, phi_lin = _linear(model.replace(Vb=V_lin))
    balance = _Balance(model, N1, psi)

    def touching(z):
        # V = Vb = exp(z[0]) > 0: the balance at the edge of its branch without reversal
        balance.kw["Vb"] = balance.Vb = math.exp(z[0])
        return balance.residual((balance.Vb, z[1]))

    sol = _hybr(touching, (math.log(V_lin), phi_lin))
    residual = np.inf if sol is None else float(np.max(np.abs(touching(sol.x))))
    if not residual <= _TOLERANCE:
        raise RuntimeError(
            f"the onset of friction reversal (V = Vb) was not found from Vb = {V_lin!r}: "
            f"residual {residual:.1e}"
        )
    return math.exp(sol.x[0])


def _check_grid(vb):
    vb = np.asarray(vb, dtype=float)
    if vb.ndim != 1 or vb.size < 2:
        raise ValueError(f"vb must be a 1-D grid of at least 2 belt speeds; got shape {vb.shape}")
    if vb.size > MAX_VB_POINTS:
        raise Refused(
            f"vb has {vb.size} belt speeds, more than MAX_VB_POINTS = {MAX_VB_POINTS:.0e} "
            "(beltmdsm/settings.py)",
            "points",
        )
    if not np.all(np.isfinite(vb)) or np.any(vb < 0):
        raise ValueError("vb must hold finite belt speeds >= 0")
    return vb


#: The grid gets a point this far below the linear amplitude ``V_lin``, relative, and
#: none between it and ``V_lin``: the damping there is that of the onset of reversal.
#: Closer to ``V_lin`` the harmonic balance can be singular: at the base set its
#: reversing solution keeps ``V - Vb = 2.1e-3 m/s`` up to ``V_lin`` (the damping tends
#: to -18.4), but where the excitation is at resonance (``Omega = omega1``) the
#: reversal vanishes as ``(V_lin - Vb)^2``, and within 1e-8 of ``V_lin`` it is below the
#: rounding of ``V`` (no solution can be resolved). At 1e-4 both are resolved (the
#: residual 7e-12 at resonance, 5e-16 at the base set), with the sign of their limits.
ONSET_STEP = 1e-4


def _check_points(points):
    if isinstance(points, bool) or not isinstance(points, (int, np.integer)) or points < 2:
        raise ValueError(f"points must be an integer >= 2; got {points!r}")
    if points > MAX_VB_POINTS:
        raise Refused(
            f"points = {points} is more than MAX_VB_POINTS = {MAX_VB_POINTS:.0e} "
            "(beltmdsm/settings.py): up to 2 ms a point (6 ms under a law whose fast "
            "average is a quadrature), and every edge is "
            "refined to 1e-10 m/s anyway",
            "points",
        )


def unstable_intervals(
    model: Model | Mapping[str, Any] | None = None,
    *,
    vb: ArrayLike | None = None,
    points: int | np.integer = 400,
    progress: bool = False,
    vb_max: float | None = None,
    **kw: Any,
) -> tuple[list[tuple[float, float]], dict[str, NDArray[Any]]]:
    """Unstable belt speeds of the consistent MDSM.

    The damping is evaluated on a grid (continuation from high ``Vb`` down, where the
    friction does not reverse), and each change of sign is refined by bisection
    (``brentq``, to 1e-10 m/s) at a root of the damping; at the onset of friction
    reversal (`reversal_onset`: below it the friction reverses within a fast cycle,
    above it not, and the damping jumps) the edge is the onset itself: for Coulomb's
    law the linear amplitude ``V_lin`` in closed form.

    The edges are found on the grid with the onset and a point `ONSET_STEP` below it
    added (where they lie within the grid) and the grid's points between them left
    out (the balance may be singular there; in the table they hold the damping where
    it can be solved, else NaN), so that this edge is found on any grid, however
    coarse or fine: with 2 points the band of the base set is [4.682, 6.375], as with
    400 or 30000. An edge at a root
    of the damping is found wherever the damping changes sign between neighbours; a
    band narrower than the grid step (two roots between neighbours) can be missed,
    and a band that reaches the lowest point of the grid may extend below it
    (`predict` says so).

    Parameters
    ----------
    vb : array_like, optional
        the grid of belt speeds (at least 2, at most `MAX_VB_POINTS`, finite, >= 0);
        default: ``points`` speeds up to 1.05 times the onset of reversal; for a
        friction coefficient that varies in slip up to 1.05 times the onset plus the
        unforced critical belt speed (`beltmdsm.generated.unforced.critical_belt_speed`, where
        it is finite: above the onset the fast motion still sweeps the falling part
        of the law), doubled up to 3 times while a band reaches the top
    points : int
        size of the default grid (at least 2, at most `MAX_VB_POINTS`)
    progress : bool
        show a progress bar on stderr (tqdm) once the grid takes more than 2 s
    vb_max : float, optional
        the top of the grid instead of the default's (``vb`` not given): ``points``
        speeds up to it, and, where it lies above the default's top, the default grid
        below that too, so that a coarse grid keeps the default's resolution where the
        bands are (``--vb-max 3000``: a step of 7.5 m/s missed the base set's band
        [4.682, 6.375] entirely); `grid_note` says what the coarse part cannot resolve

    Returns
    -------
    intervals : list of (lower, upper)
        Unstable ranges of ``Vb`` within the grid (an end of the grid bounds a range
        that reaches it). Without excitation (no fast motion) and a coefficient
        constant in slip the list is empty and so is the default grid.
    table : dict of arrays
        ``Vb``, ``damping``, ``V``, ``theta``, ``reverses`` on the grid asked for
        (ascending).

    Raises
    ------
    ValueError
        For bad parameters or a bad grid (naming them), for two excitation
        frequencies (the harmonic balance needs one), for laws whose normal motion
        depends on the tangential one (`beltmdsm.model.Unsupported`);
        `beltmdsm.errors.Refused` for a grid of more than `MAX_VB_POINTS` points.
    RuntimeError
        If the harmonic balance does not converge at a belt speed.
    """
    model = as_model(model, **kw)
    _check_points(points)
    _single_frequency(model.params)
    require(model, "one_way_coupling", "the consistent MDSM's fast normal force")
    onset = reversal_onset(model)
    if vb is not None:
        return _scan(model, _check_grid(vb), onset, progress)
    # Above the onset the friction never reverses (for Coulomb's law the slope of its
    # average is 0 there); a coefficient that varies with the sliding speed keeps a
    # slope while the fast motion reaches its steep part: the unforced critical belt
    # speed is added, and the grid is doubled (up to `_EXTEND` times) while a band
    # reaches its top.
    linear = _linear_without_reversal(model)
    top = _default_top(model, onset)
    if vb_max is not None:
        if not (math.isfinite(vb_max) and vb_max > 0):
            raise ValueError(f"vb_max must be a finite belt speed > 0; got {vb_max!r}")
        grid = np.linspace(vb_max / points, vb_max, points)
        if top > 0:
            fine = np.linspace(top / points, top, points)
            grid = np.union1d(grid, fine[fine < vb_max])
        return _scan(model, grid, onset, progress)
    if not top > 0:
        return _scan(model, np.empty(0), onset, progress)
    for extend in range(_EXTEND + 1):
        vb = np.linspace(top / points, top, points)
        found, table = _scan(model, vb, onset, progress)
        if linear or not (found and found[-1][1] == vb[-1]) or extend == _EXTEND:
            return found, table
        top *= 2
    raise AssertionError("unreachable")


#: How often the default grid of a law whose coefficient varies in slip is doubled
#: while an unstable band reaches its top (`unstable_intervals`).
_EXTEND = 3


def _scan(model: Model, vb: NDArray[np.float64], onset: float, progress: bool):
    """`unstable_intervals` on the grid ``vb`` (checked), with the onset of reversal."""
    requested = np.sort(vb)
    zone = np.zeros(vb.size, bool)
    if vb.size and onset > 0:
        # the onset of reversal and a point just below it; the requested points between
        # them are evaluated for the table only (the balance may be singular there)
        onset_below = onset * (1 - ONSET_STEP)
        zone = (requested > onset_below) & (requested < onset)
        extra = [v for v in (onset_below, onset) if vb.min() < v < vb.max()]
        vb = np.union1d(requested[~zone], extra)
    if vb.size == 0:
        return [], {
            "Vb": vb,
            "damping": vb.copy(),
            "V": vb.copy(),
            "theta": vb.copy(),
            "reverses": np.zeros(0, bool),
        }
    from tqdm import tqdm

    rows, guess = [], None
    total = vb.size + int(zone.sum())
    bar = tqdm(
        total=total, desc="predict Vb", disable=not progress, file=sys.stderr, delay=2, leave=False
    )
    try:
        for v in sorted(vb, reverse=True):
            q = model.replace(Vb=float(v))
            fast = fast_motion(q, guess)
            guess = fast
            rows.append((v, consistent_mdsm_damping(q, fast), fast))
            bar.update()
        rows.sort(key=lambda r: r[0])
        found = {float(r[0]): r[1:] for r in rows}
        for v in requested[zone]:
            q = model.replace(Vb=float(v))
            try:
                fast = fast_motion(q, found[float(onset_below)][1])
                found[float(v)] = (consistent_mdsm_damping(q, fast), fast)
            except RuntimeError:
                found[float(v)] = (math.nan, None)
            bar.update()
    finally:
        bar.close()
    grid = np.array([r[0] for r in rows])
    damping = np.array([r[1] for r in rows])

    def damping_at(v, guess):
        q = model.replace(Vb=float(v))
        return consistent_mdsm_damping(q, fast_motion(q, guess))

    cuts = []
    for i in intervals.sign_changes(damping):
        below, above = rows[i][2], rows[i + 1][2]
        if below.reverses != above.reverses:
            # Onset of reversal: the edge is the onset itself (for Coulomb's law the
            # linear amplitude, independent of Vb); the harmonic balance is singular
            # there and no root-finder is needed.
            cuts.append(_onset_between(model, onset, grid[i], grid[i + 1]))
            continue
        cuts.append(optimize.brentq(damping_at, grid[i], grid[i + 1], args=(above,), xtol=1e-10))
    unstable = intervals.from_crossings(grid, damping < 0, cuts)
    at = [found[float(v)] for v in requested]
    table = {
        "Vb": requested,
        "damping": np.array([d for d, _ in at]),
        "V": np.array([f.V if f else math.nan for _, f in at]),
        "theta": np.array([f.theta if f else math.nan for _, f in at]),
        "reverses": np.array([bool(f and f.reverses) for _, f in at]),
    }
    return unstable, table


def _default_top(model: Model, onset: float) -> float:
    """The top of the default grid (before any doubling): 1.05 times the onset of
    reversal, plus the unforced critical belt speed for a coefficient that varies in slip."""
    linear = _linear_without_reversal(model)
    return 1.05 * (onset + (0.0 if linear else _unforced_edge(model)))


def grid_note(
    model: Model | Mapping[str, Any] | None = None,
    *,
    vb_max: float,
    points: int = 400,
    **kw: Any,
) -> str:
    """What a grid of ``points`` speeds up to ``vb_max`` cannot resolve ("" if nothing).

    Where ``vb_max`` lies above the default grid's top, `unstable_intervals` keeps the
    default grid below that top; above it the step is ``vb_max / points``, and a band
    narrower than that there can be missed.
    """
    model = as_model(model, **kw)
    onset = reversal_onset(model)
    top = _default_top(model, onset)
    step = vb_max / points
    if not top > 0 or top >= vb_max or step <= top / points:
        return ""
    return GRID_COARSE.format(top=top, fine=top / points, step=step)


#: Where the unforced growth rate's roots are looked for when the law's closed form is
#: refused (`unforced_edges`): 1e-8 to 1e8 m/s, 100 speeds a decade (a ratio of 2.3 %
#: between neighbours: a band narrower than that can be missed).
UNFORCED_SCAN = (1e-8, 1e8, 100)


def unforced_rate(model: Model | Mapping[str, Any] | None, vb: ArrayLike) -> NDArray:
    """The largest real part of `beltmdsm.generated.unforced.eigenvalues` at each belt speed:
    steady sliding is unstable where it is positive."""
    model = as_model(model)
    fn = unforced.eigenvalues
    args = {**model.arguments(fn), "Vb": np.asarray(vb, dtype=float)}
    return np.max(np.real(fn(**args)), axis=-1)


def unforced_edges(model: Model | Mapping[str, Any] | None = None, **kw: Any) -> list[float]:
    """The belt speeds where steady sliding changes stability, numerically.

    The roots of `unforced_rate` over `UNFORCED_SCAN` (a geometric grid), each sign
    change refined by ``brentq`` to 1e-12 relative: the path where the law's closed
    form (`beltmdsm.generated.unforced.critical_belt_speed`) is refused. A band narrower than
    the scan's ratio (2.3 %) can be missed.
    """
    model = as_model(model, **kw)
    lo, hi, per_decade = UNFORCED_SCAN
    vb = np.geomspace(lo, hi, int(round(per_decade * math.log10(hi / lo))) + 1)
    rate = unforced_rate(model, vb)
    edges = []
    for i in intervals.sign_changes(rate):
        edges.append(
            optimize.brentq(
                lambda v: float(unforced_rate(model, [v])[0]),
                vb[i],
                vb[i + 1],
                xtol=1e-300,
                rtol=1e-12,
            )
        )
    return edges


def _unforced_edge(model: Model) -> float:
    """The unforced critical belt speed (`beltmdsm.generated.unforced.critical_belt_speed`) where it
    is finite and positive; where the law's closed form is refused, the largest of
    `unforced_edges`; else 0."""
    fn = unforced.critical_belt_speed
    try:
        edge = float(fn(**model.arguments(fn)))
    except ValueError:  # a law without a closed-form boundary refuses (Unsupported)
        edges = unforced_edges(model)
        return max(edges) if edges else 0.0
    return edge if math.isfinite(edge) and edge > 0 else 0.0


def _unforced_note(model: Model) -> str:
    """Where the unforced critical speed's closed form is refused: how it was found."""
    fn = unforced.critical_belt_speed
    try:
        fn(**model.arguments(fn))
    except ValueError as err:
        edges = unforced_edges(model)
        found = ", ".join(f"{v:.6g}" for v in edges) or "none"
        return UNFORCED_NUMERIC.format(why=err, edges=found)
    return ""


def _onset_between(model: Model, onset: float, lo: float, hi: float) -> float:
    """The onset of reversal within ``[lo, hi]``: the one found first, or another one
    of a law whose fast amplitude varies with ``Vb`` (`reversal_onset` from ``hi``)."""
    if lo <= onset <= hi:
        return onset
    other = reversal_onset(model, start=hi)
    if not lo <= other <= hi:
        raise RuntimeError(
            f"the friction starts to reverse between Vb = {lo!r} and {hi!r}, but the "
            f"onset (V = Vb) was not found there (found {other!r})"
        )
    return other


def paper_intervals(
    model: Model | Mapping[str, Any] | None = None,
    *,
    convention: Literal["paper", "consistent"] = "paper",
    **kw: Any,
) -> dict[str, list[tuple[float, float]] | None]:
    """The paper's unstable interval ``(Vb_c, Vhat]`` for each ``V_hat`` reading (Eq. 25, 28).

    With the model's laws (`beltmdsm.generated.stability.unstable_interval` and
    `beltmdsm.generated.friction.vhat` get ``friction=`` and ``contact=``). Where the closed form
    does not exist (the law's fast average is no closed form, the capability
    ``closed_form_average``, Stribeck's; or ``V_hat`` depends on ``Vb``) the same
    analysis is solved numerically (`paper_numeric`).

    Parameters
    ----------
    model : Model, mapping or None
        the parameter set (or the keywords ``**kw`` it is built from)
    convention : {"paper", "consistent"}
        the sign of the effective friction in Eq. (A4): as printed, or as Eq. (4)
        implies (`beltmdsm.generated.stability.unstable_interval`, docs/modelling.md#friction-sign)

    Returns
    -------
    dict
        ``{"tangential": [(lower, upper), ...], "coupled": [...]}``; an empty interval
        (NaN from `beltmdsm.generated.stability.unstable_interval`) is ``[]``, and a reading
        without an answer is ``None``: ``V_hat`` is 0 (no excitation, where Eqs. 23-25
        have no meaning). `paper_reasons` says why, or how a numeric set was found.
    """
    return _paper(as_model(model, **kw), convention)[0]


def paper_reasons(
    model: Model | Mapping[str, Any] | None = None,
    *,
    convention: Literal["paper", "consistent"] = "paper",
    **kw: Any,
) -> dict[str, str]:
    """``{reading: why}`` for each ``V_hat`` reading whose `paper_intervals` is None
    (`NO_VHAT`, or the refusal of `beltmdsm.generated.stability.unstable_interval`) or was found
    numerically (`PAPER_NUMERIC`: why there is no closed form, the grid and the
    tolerance): one line each."""
    return _paper(as_model(model, **kw), convention)[1]


def _vhat_depends_on_vb(model: Model, reading: str) -> bool:
    """Whether the law's ``V_hat`` takes ``Vb`` (the slope of a coefficient that varies
    in slip enters the linear response): the generated function then needs it."""
    fn = friction.vhat
    try:
        fn(model=reading, **{**model.arguments(fn), "Vb": None})
    except TypeError:
        return True
    return False


#: Points of the grid of `paper_numeric` (from ``Vb = 0``); the growth rate under a
#: quadrature costs about 20 us a point, vectorised.
PAPER_POINTS = 2000
#: The tolerance of `paper_numeric`'s edges (brentq's ``xtol``) [m/s].
PAPER_XTOL = 1e-12
#: How far (relative) either side of a crossing ``V_hat(Vb) = Vb`` `paper_numeric` puts
#: grid points: the slope of Eq. (25) jumps there, and a change of stability between
#: them is an edge at the crossing itself.
_CROSSING_STEP = 1e-9


def _grid_top(model: Model, kw_vhat: dict) -> float:
    """The default top of `paper_numeric`'s grid: 1.05 times ``V_hat(0)`` plus the
    unforced critical belt speed (as the consistent MDSM's grid: above ``V_hat`` the
    fast motion still sweeps the falling part of a law like Stribeck's)."""
    v0 = float(friction.vhat(**{**kw_vhat, "Vb": 0.0}))
    return 1.05 * (v0 + _unforced_edge(model))


def paper_numeric(
    model: Model | Mapping[str, Any] | None = None,
    *,
    reading: Literal["tangential", "coupled"] = "tangential",
    convention: Literal["paper", "consistent"] = "paper",
    points: int = PAPER_POINTS,
    **kw: Any,
) -> tuple[list[tuple[float, float]], dict[str, Any]]:
    """The unstable belt speeds of the paper's analysis without its closed form.

    The set where `beltmdsm.generated.stability.growth_rate` (Eq. 26 with Eqs. 23-25; the
    effective friction and its slope a quadrature of the law's expression where the
    law has no closed-form fast average) is positive, with ``V_hat`` of ``reading``
    (`beltmdsm.generated.friction.vhat`) evaluated at each ``Vb``: the reading implemented is
    the fast amplitude of the equilibrium at that belt speed, held fixed in the slow
    linearisation (the slope is ``d mu_bar / d Vr`` at fixed ``V_hat``, not the total
    derivative in ``Vb``). For Coulomb's law it is the closed form's set, to the
    tolerance (`tests/beltmdsm/prediction/test_predict.py`).

    On ``points`` belt speeds from 0 up to `_grid_top` (doubled up to 3 times while
    a band reaches it) plus the points either side of each crossing ``V_hat(Vb) = Vb``
    (found by brentq), each change of sign of the growth rate between neighbours is
    an edge: the crossing itself where the two sit either side of one (the slope of
    Eq. 25 jumps there), else a root of the growth rate refined by brentq to
    `PAPER_XTOL`. A band narrower than the grid step can be missed.

    Returns
    -------
    intervals : list of (lower, upper)
    info : dict
        ``top`` (the grid's end), ``points``, ``step``, ``crossings`` (the belt speeds
        where ``V_hat(Vb) = Vb``), ``reaches_top`` (a band ends at the grid's end).

    Raises
    ------
    ValueError
        Where ``V_hat`` is not positive on the grid (no fast motion: Eqs. 23-25
        need ``V_hat > 0``; the message is `NO_VHAT`).
    """
    model = as_model(model, **kw)
    grow, fv = stability.growth_rate, friction.vhat
    kw_grow = {**model.arguments(grow), "convention": convention, "vhat_model": reading}
    kw_vhat = {**model.arguments(fv), "model": reading}

    def sigma(vb):
        return grow(**{**kw_grow, "Vb": vb})

    def gap(vb):
        return vb - fv(**{**kw_vhat, "Vb": vb})

    top = _grid_top(model, kw_vhat)
    if not top > 0:
        raise ValueError(NO_VHAT)
    for extend in range(_EXTEND + 1):
        base = np.linspace(0.0, top, points)
        g = gap(base)
        if not np.all(g < base):
            raise ValueError(NO_VHAT)
        crossings = [
            optimize.brentq(gap, base[i], base[i + 1], xtol=PAPER_XTOL)
            for i in intervals.sign_changes(g)
        ]
        sides = [c * (1 + d * _CROSSING_STEP) for c in crossings for d in (-1, 1)]
        grid = np.union1d(base, [v for v in sides if 0 < v < top])
        s = sigma(grid)
        cuts = []
        for i in intervals.sign_changes(-s):
            lo, hi = grid[i], grid[i + 1]
            at = [c for c in crossings if lo <= c <= hi]
            if at:
                cuts.append(at[0])
            else:
                cuts.append(optimize.brentq(sigma, lo, hi, xtol=PAPER_XTOL))
        found = intervals.from_crossings(grid, s > 0, cuts)
        reaches = bool(found and found[-1][1] == grid[-1])
        if not reaches or extend == _EXTEND:
            break
        top *= 2
    info = {
        "top": float(top),
        "points": int(grid.size),
        "step": float(top / (points - 1)),
        "crossings": [float(c) for c in crossings],
        "reaches_top": reaches,
    }
    return found, info


def _paper(model: Model, convention: str):
    intervals_, reasons = {}, {}
    closed = model.fact("closed_form_average")[0]
    fn = friction.vhat
    for reading in ("tangential", "coupled"):
        intervals_[reading] = None
        if not closed:
            without = NUMERIC_NO_AVERAGE.format(friction=model.friction)
        elif _vhat_depends_on_vb(model, reading):
            without = NUMERIC_VHAT_OF_VB.format(friction=model.friction)
        elif not fn(model=reading, **model.arguments(fn)) > 0:
            reasons[reading] = NO_VHAT
            continue
        else:
            interval = stability.unstable_interval
            try:
                lower, upper = (
                    float(x)
                    for x in interval(
                        convention=convention, vhat_model=reading, **model.arguments(interval)
                    )
                )
            except _support.Unsupported as err:  # no closed-form boundary for these laws
                reasons[reading] = str(err)
                continue
            # an empty interval is NaN (also (Vb_c, Vhat] with Vb_c = Vhat: mu_s = 0)
            empty = math.isnan(lower) or not lower < upper
            intervals_[reading] = [] if empty else [(lower, upper)]
            continue
        try:
            found, info = paper_numeric(model, reading=reading, convention=convention)
        except ValueError as err:
            reasons[reading] = str(err)
            continue
        intervals_[reading] = found
        note = PAPER_NUMERIC.format(without=without, reading=reading, xtol=PAPER_XTOL, **info)
        if info["reaches_top"]:
            note += "; " + GRID_END.format(end="highest", value=info["top"], side="above")
        reasons[reading] = note
    return intervals_, reasons


#: Why an analysis gives no prediction, or none of its usual kind.
NO_EXCITATION = (
    "no fast tangential motion: without tangential excitation, and none passed "
    "on by friction from the normal one, the averaged friction is friction of "
    "constant direction and coefficient with slope 0, so no belt speed is unstable"
)
#: The note on the consistent MDSM without fast motion, for a coefficient that
#: varies in slip (formatted with the law).
NO_FAST_MOTION = (
    "no fast tangential motion: the slow damping is the unforced equilibrium's, "
    "2 beta1 omega1 + g dmu/d|Vr| at |Vr| = Vb (beltmdsm.generated.unforced), which varies "
    "with Vb under friction={friction!r}"
)
NO_VHAT = "V_hat = 0 (no fast tangential motion): Eqs. (23)-(25) need V_hat > 0"
#: How `paper_intervals` found a set without the closed form (formatted with the reason
#: there is none, the reading and `paper_numeric`'s grid).
PAPER_NUMERIC = (
    "numeric ({without}: Eqs. (25), (28) have no closed form): Vb where "
    "beltmdsm.generated.stability.growth_rate > 0 with V_hat ({reading} reading) at each Vb, "
    "{points} points in [0, {top:.4g}] m/s, edges by brentq to {xtol:.0e} m/s (a root, "
    "or V_hat(Vb) = Vb where the slope of Eq. (25) jumps); a band narrower than "
    "{step:.2g} m/s can be missed"
)
#: The clauses of `PAPER_NUMERIC`: a law without a closed-form fast average, a V_hat
#: that depends on Vb.
NUMERIC_NO_AVERAGE = "friction={friction!r} has no closed-form fast average (closed_form_average)"
NUMERIC_VHAT_OF_VB = "V_hat depends on Vb under friction={friction!r}"
#: The note on a grid whose step above the default's top is coarser than the default's
#: (formatted with the default top, its step and the coarse step).
GRID_COARSE = (
    "the grid keeps the default's step {fine:.3g} m/s up to {top:.4g} m/s; above it the "
    "step is {step:.3g} m/s, and a band narrower than that there can be missed"
)
#: How the unforced critical belt speed was found where the law's closed form is
#: refused (formatted with the refusal and the edges found).
UNFORCED_NUMERIC = (
    "the unforced critical belt speed has no closed form ({why}); steady sliding "
    "changes stability at Vb = {edges} m/s, the roots of the largest real part of "
    "beltmdsm.generated.unforced.eigenvalues over 1e-8..1e8 m/s (100 speeds a decade, brentq "
    "to 1e-12 relative; a band narrower than 2.3 % can be missed)"
)
#: The note on a band of the consistent MDSM that reaches an end of its grid.
GRID_END = (
    "an unstable range reaches the {end} belt speed of the grid, {value:.4g} m/s, "
    "and may extend {side} it"
)
#: Why the consistent MDSM gives no prediction under the clipped tension law
#: (formatted with the amplitude ``N1`` of the fast normal force and ``g``).
CLIPPED_MDSM = (
    "tension='clipped': the harmonic balance of the consistent MDSM assumes a "
    "harmonic fast normal force g + N1 sin(Omega t + psi), and with N1 = {N1:.4g} "
    ">= g = {g:.4g} the clip max(F, 0) cuts it off wherever it would pull, which "
    "makes it non-harmonic; no prediction (the allowed law's would be silently "
    "wrong)"
)
#: The note on the consistent MDSM where the clip does not act on its fast normal force.
CLIPPED_MDSM_INACTIVE = (
    "tension='clipped': the linear fast normal force g + N1 sin stays "
    "positive (N1 = {N1:.4g} < g = {g:.4g}), so the clip does not act on "
    "it and the harmonic balance is the same as under 'allowed'"
)
#: The note on every analysis under a friction law with a static bound of its own
#: (``beltmdsm.generated.parameters.STATIC_BOUNDS``; formatted with the law and both bounds).
STATIC_BOUND = (
    "friction={friction!r}: averaged is the slip law (mu(0) = {rest}) over a fast "
    "motion that passes Vr = 0 without sticking; the static bound {static} bounds "
    "stick only, so a belt speed found stable here does not exclude a stick-slip "
    "cycle beside stable sliding (friction_monotone fails where {rest} < {static})"
)
#: The note on the paper's closed forms under the clipped tension law.
CLIPPED_PAPER = (
    "tension='clipped': the same as under 'allowed', since the analysis "
    "linearises at the equilibrium, where the contact force g > 0 does not pull"
)


class _Refused(Exception):
    """An analysis that gives no prediction, with the reason."""


def clip_acts(model: Model) -> tuple[bool, float]:
    """``(acts, N1)``: whether the clip cuts the linear fast normal force ``g + N1 sin``.

    True when ``N1 >= g`` (the force would reach zero within a fast cycle), with
    ``N1`` from `beltmdsm.generated.correlation.fast_normal_force`.
    """
    N1 = _normal(model)[0]
    return N1 >= model["g"], N1


@dataclass(frozen=True)
class Prediction:
    """The predicted unstable ``Vb`` intervals of each analysis (``predict --json`` keys).

    Each of ``paper_tangential_vhat``, ``paper_coupled_vhat`` and ``consistent_mdsm``
    is a list of ``(lower, upper)``, or None where the analysis has no answer;
    ``reasons`` maps an analysis to the sentence that says why it has none, or why
    its list is empty or what it assumed (no excitation, the tension law).
    """

    paper_tangential_vhat: list[tuple[float, float]] | None
    paper_coupled_vhat: list[tuple[float, float]] | None
    consistent_mdsm: list[tuple[float, float]] | None
    reasons: dict[str, str] = field(default_factory=dict)
    tension: str = OPTION_DEFAULTS["tension"]
    contact: str = OPTION_DEFAULTS["contact"]
    friction: str = OPTION_DEFAULTS["friction"]

    #: The analyses, in the order they are printed.
    ANALYSES = ("paper_tangential_vhat", "paper_coupled_vhat", "consistent_mdsm")

    def as_dict(self) -> dict[str, Any]:
        return asdict(self)


def predict(
    model: Model | Mapping[str, Any] | None = None,
    *,
    vb: ArrayLike | None = None,
    points: int | np.integer = 400,
    progress: bool = False,
    vb_max: float | None = None,
    **kw: Any,
) -> Prediction:
    """Both analyses' predicted unstable ``Vb`` intervals.

    Parameters
    ----------
    model : Model or dict, optional
        ``tension`` (docs/modelling.md#tension): the paper's closed forms do not
        change with it (a note in ``reasons`` says why); the consistent MDSM under
        ``"clipped"`` has no prediction where the clip cuts its fast normal force
        (`clip_acts`, `CLIPPED_MDSM`) and a note where it does not.
    vb, points, progress, vb_max
        the ``Vb`` grid of the consistent MDSM and its progress bar
        (`unstable_intervals`). Where a band of the consistent MDSM reaches the
        lowest point of the grid above 0, ``reasons`` says that it may extend below;
        where ``vb_max`` makes the grid coarser than the default's, what it cannot
        resolve (`grid_note`); where the law's unforced critical belt speed has no
        closed form, that its edges were found numerically (`unforced_edges`).

    Returns
    -------
    Prediction

    Raises
    ------
    ValueError
        For bad parameters, a bad option or a bad grid (naming them);
        `beltmdsm.errors.Refused` for more than `MAX_VB_POINTS` points.
    """
    model = as_model(model, **kw)
    p, tension = model.params, model.tension
    _check_points(points)
    if vb is not None:
        vb = _check_grid(vb)
    reasons = {}
    clipped = False
    if tension == "clipped" and p["Omega_t"] == p["Omega_n"]:
        # (with two frequencies the harmonic balance is refused for that reason below)
        clipped, N1 = clip_acts(model)
        note = (CLIPPED_MDSM if clipped else CLIPPED_MDSM_INACTIVE).format(N1=N1, g=p["g"])
    try:
        if clipped:
            raise _Refused(note)
        consistent, table = unstable_intervals(
            model, vb=vb, points=points, progress=progress, vb_max=vb_max
        )
    except _Refused as err:
        consistent, reasons["consistent_mdsm"] = None, str(err)
    except RuntimeError as err:
        consistent, reasons["consistent_mdsm"] = None, str(err)
    except ValueError as err:
        # the parameters and the grid are checked above: what is left is the
        # analysis' own limit (one excitation frequency, laws whose normal motion
        # depends on the tangential one: beltmdsm.model.Unsupported)
        consistent, reasons["consistent_mdsm"] = None, str(err)
    else:
        if _linear(model)[0] == 0:
            reasons["consistent_mdsm"] = (
                NO_EXCITATION
                if _linear_without_reversal(model)
                else NO_FAST_MOTION.format(friction=model.friction)
            )
        ends = []
        if not _linear_without_reversal(model):
            ends.append(_unforced_note(model))
        if vb is None and vb_max is not None:
            ends.append(grid_note(model, vb_max=vb_max, points=int(points)))
        if table["Vb"].size:
            lowest, highest = float(table["Vb"][0]), float(table["Vb"][-1])
            if lowest > 0 and any(lo == lowest for lo, _ in consistent):
                ends.append(GRID_END.format(end="lowest", value=lowest, side="below"))
            if any(hi == highest for _, hi in consistent):
                ends.append(GRID_END.format(end="highest", value=highest, side="above"))
        if any(ends):
            reasons["consistent_mdsm"] = "; ".join(
                r for r in (reasons.get("consistent_mdsm"), *ends) if r
            )
        if tension == "clipped":
            reasons["consistent_mdsm"] = "; ".join(
                r for r in (reasons.get("consistent_mdsm"), note) if r
            )
    paper, why = _paper(model, "paper")
    for key, reading in (
        ("paper_tangential_vhat", "tangential"),
        ("paper_coupled_vhat", "coupled"),
    ):
        note = why.get(reading)
        if tension == "clipped" and paper[reading] is not None:
            note = "; ".join(r for r in (note, CLIPPED_PAPER) if r)
        if note:
            reasons[key] = note
    if model.friction in STATIC_BOUNDS:
        static, rest = STATIC_BOUNDS[model.friction]
        text = STATIC_BOUND.format(friction=model.friction, static=static, rest=rest)
        for key in Prediction.ANALYSES:
            reasons[key] = "; ".join(r for r in (reasons.get(key), text) if r)
    return Prediction(
        paper["tangential"],
        paper["coupled"],
        consistent,
        reasons,
        tension,
        model.contact,
        model.friction,
    )
