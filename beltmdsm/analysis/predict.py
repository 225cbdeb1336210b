"""Predicted unstable belt speeds: the paper's analysis and a consistent MDSM.

The paper (Sects. 4.2-4.3) linearises the slow equations with the slope ``mu_bar'`` of
Eq. (25); `generated.stability` gives its unstable interval in closed form. The
consistent analysis here keeps what the paper drops (docs/modelling.md#averaging): the
correlation between the fast friction direction and the fast normal force.

For a belt speed ``Vb`` it

1. takes the fast normal force ``N(t) = g + N1 sin(Omega t + psi)`` from the linear
   normal response (`generated.correlation.fast_normal_force`; the normal motion does
   not depend on the tangential one);
2. finds the fast relative velocity ``V sin(Omega t + phi)`` by harmonic balance of the
   tangential equation (Eq. A1) with Coulomb friction in the sign of Eq. (4): linear
   (the coupled ``V_hat``) while ``V <= Vb``; otherwise the friction reverses within a
   fast cycle and its first harmonic (`generated.correlation.first_harmonic`) closes a
   two-unknown nonlinear system, solved by Newton iterations continued in ``Vb``;
3. linearises the averaged friction ``mu_s <sgn(Vr) N>`` in the slow velocity at
   frozen fast amplitude and phase (`generated.correlation.averaged_friction_slope`):
   the tangential damping is ``p = 2 beta1 omega1 + mu_s dF/du``, unstable when ``p < 0``
   (the normal block is that of Eq. 22 and always stable).

Only one excitation frequency is covered (``Omega_t == Omega_n``): with two frequencies
a single harmonic balance does not apply and `consistent_mdsm_damping` raises.

The tension law (`predict`'s ``tension=``, docs/modelling.md#tension): the paper's
analyses linearise at the equilibrium, where the contact force is ``g > 0``, so
their closed forms are the same under both laws. The consistent MDSM takes a
harmonic fast normal force ``g + N1 sin``; with ``tension="clipped"`` and
``N1 >= g`` the clip ``max(F, 0)`` cuts it off and it is no longer harmonic, so that
analysis gives no prediction (`CLIPPED_MDSM`) rather than the allowed law's.
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

from generated import correlation, friction, stability

from .. import intervals
from ..errors import Refused
from ..model import Model, as_model
from ..settings import MAX_VB_POINTS

__all__ = [
    "FastMotion",
    "fast_motion",
    "consistent_mdsm_damping",
    "unstable_intervals",
    "paper_intervals",
    "predict",
    "Prediction",
    "NO_EXCITATION",
    "NO_VHAT",
    "CLIPPED_MDSM",
    "CLIPPED_PAPER",
    "clip_acts",
    "ONSET_STEP",
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


def _balance(z, p, W, N1, psi, D, Ft):
    """Residual of D V/(i W) = Ft e^{-i phi} - mu_s (s1 + i c1), scaled by |Ft|."""
    V, phi = z
    s1, c1 = correlation.first_harmonic(-p["Vb"], V, p["g"], N1, psi - phi)
    r = D * V / (1j * W) - Ft * np.exp(-1j * phi) + p["mu_s"] * (s1 + 1j * c1)
    return np.array([r.real, r.imag]) / abs(Ft)


def _log_balance(z, *args):
    """`_balance` in ``(log V, phi)``: every iterate keeps ``V > 0``."""
    return _balance((np.exp(z[0]), z[1]), *args)


def _reversing_balance(z, *args):
    """`_balance` in ``(s, phi)`` with ``V = Vb + s^2``: every iterate reverses.

    At the onset of reversal (``V = Vb``) the first harmonic of the friction has a
    square-root singularity in ``V``: the reversal lasts a phase interval of width
    proportional to ``sqrt(V - Vb)``. In ``s`` it is smooth, so Newton's method
    converges next to the linear amplitude, where it stalls in ``V``.
    """
    return _balance((args[0]["Vb"] + z[0] ** 2, z[1]), *args)


def _hybr(fun, start, args):
    """``scipy.optimize.root`` (hybr) from ``start``; None if an iterate had ``V <= 0``."""
    try:
        return optimize.root(fun, start, args=args, method="hybr", options={"xtol": 1e-13})
    except ValueError:
        # the generated first_harmonic refuses V <= 0 (checked before the Vb loop, the
        # parameters themselves are valid here)
        return None


#: The shallowest reversal a solution of the harmonic balance may have, relative to
#: ``V``: ``V - Vb`` of 1024 ulps of ``V``. Below it the first harmonic of the friction
#: (``sqrt(1 - Vb^2 / V^2)``) carries a relative rounding error of about
#: ``eps V / (2 (V - Vb))``, over 5e-4, and a near-root at ``V -> Vb`` (no reversal)
#: can pass the residual test next to the linear amplitude.
_SHALLOWEST_REVERSAL = 1024 * np.finfo(float).eps


def fast_motion(model: Model, guess: FastMotion | None = None) -> FastMotion:
    """The fast motion at the model's ``Vb``.

    Parameters
    ----------
    guess : FastMotion, optional
        Start of the Newton iterations (continuation from a neighbouring ``Vb``);
        default: the linear solution.

    Raises
    ------
    RuntimeError
        If the harmonic balance does not converge.
    """
    p, contact = model.params, model.contact
    W = _single_frequency(p)
    N1, psi = (float(x) for x in correlation.fast_normal_force(contact=contact, **p))
    D = p["omega1"] ** 2 - W**2 + 2j * p["beta1"] * p["omega1"] * W
    Ft = p["alpha_t"] * W**2 * np.exp(1j * p["phase_t"])
    # Friction of constant direction (Vr < 0 throughout): the linear, coupled response.
    V_lin, phi_lin = (float(x) for x in correlation.fast_tangential_velocity(contact=contact, **p))
    if V_lin <= p["Vb"]:
        return FastMotion(V_lin, phi_lin, N1, psi, False, 0.0)
    reversing = guess is not None and guess.reverses
    start = (guess.V, guess.phi) if reversing else (V_lin, phi_lin)
    args = (p, W, N1, psi, D, Ft)
    Vb = p["Vb"]
    # The attempts, in order: Newton's method (hybr) in V, then in log V (where V is
    # small, Vb near 0 or an excitation at resonance, a step can cross V = 0; in log V
    # it cannot), then in s = sqrt(V - Vb) (`_reversing_balance`; next to the linear
    # amplitude, where the first two stall on the square-root singularity), from the
    # guess and from reversals of 1 %, 10 % and 100 % of the linear amplitude (the
    # reversing solution there has V - Vb of the order of 1e-3 V_lin, and a start
    # below half of it falls towards s = 0, which is no solution). Tried in this
    # order, so that the cases the direct iteration solves keep their digits.
    attempts = [
        (_balance, start, lambda x: x),
        (_log_balance, (math.log(start[0]), start[1]), math.exp),
    ]
    depths = [start[0] - Vb] if start[0] > Vb else []
    depths += [f * V_lin for f in (0.01, 0.1, 1.0)]
    attempts += [
        (_reversing_balance, (math.sqrt(d), start[1]), lambda x: Vb + x * x) for d in depths
    ]
    residual, why = np.inf, ""
    for fun, z0, to_V in attempts:
        sol = _hybr(fun, z0, args)
        if sol is None:
            why = "an iterate reached V <= 0"
            continue
        V = float(to_V(sol.x[0]))
        if not V - Vb > _SHALLOWEST_REVERSAL * V:
            # the friction would not reverse, which holds only at V_lin <= Vb; or the
            # reversal is too shallow for the first harmonic to be told from rounding
            why = f"an iterate settled at V = {V!r}, without a resolved reversal (Vb = {Vb!r})"
            continue
        # hybr may report "not making good progress" once at machine precision: the
        # residual itself is the criterion.
        residual = float(np.max(np.abs(_balance((V, sol.x[1]), *args))))
        why = sol.message
        if residual <= 1e-9:
            phi = sol.x[1]
            return FastMotion(V, float(np.angle(np.exp(1j * phi))), N1, psi, True, residual)
    raise RuntimeError(
        f"harmonic balance did not converge at Vb = {Vb}: {why} (residual {residual:.1e})"
    )


def consistent_mdsm_damping(model: Model, fast: FastMotion | None = None) -> float:
    """Tangential damping ``p = 2 beta1 omega1 + mu_s dF/du`` of the slow motion at ``-Vb``."""
    p = model.params
    fast = fast or fast_motion(model)
    if fast.V == 0:
        # No fast motion (no excitation): Coulomb friction of constant direction,
        # whose average does not depend on the slow velocity.
        return float(2 * p["beta1"] * p["omega1"])
    slope = correlation.averaged_friction_slope(-p["Vb"], fast.V, p["g"], fast.N1, fast.theta)
    return float(2 * p["beta1"] * p["omega1"] + p["mu_s"] * slope)


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
            "(beltmdsm/settings.py): up to 2 ms a point, and every edge is "
            "refined to 1e-10 m/s anyway",
            "points",
        )


def unstable_intervals(
    model: Model | Mapping[str, Any] | None = None,
    *,
    vb: ArrayLike | None = None,
    points: int | np.integer = 400,
    progress: bool = False,
    **kw: Any,
) -> tuple[list[tuple[float, float]], dict[str, NDArray[Any]]]:
    """Unstable belt speeds of the consistent MDSM.

    The damping is evaluated on a grid (continuation from high ``Vb`` down, where the
    fast motion is linear), and each change of sign is refined by bisection
    (``brentq``, to 1e-10 m/s) at a root of the damping; at the onset of friction
    reversal (the linear amplitude ``V_lin``: below it the friction reverses within a
    fast cycle, above it never, and the slope of the averaged friction jumps to zero)
    the edge is the linear amplitude in closed form.

    The edges are found on the grid with ``V_lin`` and a point `ONSET_STEP` below it
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
        default: ``points`` speeds up to 1.05 times the linear amplitude of the fast
        motion
    points : int
        size of the default grid (at least 2, at most `MAX_VB_POINTS`)
    progress : bool
        show a progress bar on stderr (tqdm) once the grid takes more than 2 s

    Returns
    -------
    intervals : list of (lower, upper)
        Unstable ranges of ``Vb`` within the grid (an end of the grid bounds a range
        that reaches it). Without excitation (no fast motion) the list is empty
        and so is the default grid.
    table : dict of arrays
        ``Vb``, ``damping``, ``V``, ``theta``, ``reverses`` on the grid asked for
        (ascending).

    Raises
    ------
    ValueError
        For bad parameters or a bad grid (naming them), and for two excitation
        frequencies (the harmonic balance needs one); `beltmdsm.errors.Refused` for a
        grid of more than `MAX_VB_POINTS` points.
    RuntimeError
        If the harmonic balance does not converge at a belt speed.
    """
    model = as_model(model, **kw)
    p, contact = model.params, model.contact
    _check_points(points)
    _single_frequency(p)
    V_lin = float(correlation.fast_tangential_velocity(contact=contact, **p)[0])
    if vb is None:
        # Above the linear amplitude the friction never reverses and the slope is 0.
        top = 1.05 * V_lin
        vb = np.linspace(top / points, top, points) if top > 0 else np.empty(0)
    else:
        vb = _check_grid(vb)
    requested = np.sort(vb)
    zone = np.zeros(vb.size, bool)
    if vb.size and V_lin > 0:
        # the onset of reversal and a point just below it; the requested points between
        # them are evaluated for the table only (the balance may be singular there)
        onset_below = V_lin * (1 - ONSET_STEP)
        zone = (requested > onset_below) & (requested < V_lin)
        onset = [v for v in (onset_below, V_lin) if vb.min() < v < vb.max()]
        vb = np.union1d(requested[~zone], onset)
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
            # Onset of reversal: at V = Vb the balance is the linear one, so the edge
            # is the linear amplitude itself (independent of Vb); the harmonic balance
            # is singular there and no root-finder is needed.
            cuts.append(above.V if not above.reverses else below.V)
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


def paper_intervals(
    model: Model | Mapping[str, Any] | None = None,
    *,
    convention: Literal["paper", "consistent"] = "paper",
    **kw: Any,
) -> dict[str, list[tuple[float, float]] | None]:
    """The paper's unstable interval ``(Vb_c, Vhat]`` for each ``V_hat`` reading (Eq. 25, 28).

    Parameters
    ----------
    model : Model, mapping or None
        the parameter set (or the keywords ``**kw`` it is built from)
    convention : {"paper", "consistent"}
        the sign of the effective friction in Eq. (A4): as printed, or as Eq. (4)
        implies (`generated.stability.unstable_interval`, docs/modelling.md#friction-sign)

    Returns
    -------
    dict
        ``{"tangential": [(lower, upper)], "coupled": [...]}``; an empty interval
        (NaN from `generated.stability.unstable_interval`) is ``[]``, and a reading
        whose ``V_hat`` is 0 (no excitation, where Eqs. 23-25 have no meaning) is
        ``None``.
    """
    model = as_model(model, **kw)
    p, contact = model.params, model.contact
    out = {}
    for reading in ("tangential", "coupled"):
        if not friction.vhat(model=reading, contact=contact, **p) > 0:
            out[reading] = None
            continue
        lower, upper = (
            float(x)
            for x in stability.unstable_interval(
                convention=convention, contact=contact, vhat_model=reading, **p
            )
        )
        out[reading] = [] if math.isnan(lower) else [(lower, upper)]
    return out


#: Why an analysis gives no prediction, or none of its usual kind.
NO_EXCITATION = (
    "no fast tangential motion: without tangential excitation, and none passed "
    "on by friction from the normal one, the averaged friction is Coulomb "
    "friction with slope 0, so no belt speed is unstable"
)
NO_VHAT = "V_hat = 0 (no fast tangential motion): Eqs. (23)-(25) need V_hat > 0"
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
    ``N1`` from `generated.correlation.fast_normal_force`.
    """
    N1 = float(correlation.fast_normal_force(contact=model.contact, **model.params)[0])
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
    tension: str = "allowed"
    contact: str = "hertz_damp"
    friction: str = "coulomb"

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
    vb, points, progress
        the ``Vb`` grid of the consistent MDSM and its progress bar
        (`unstable_intervals`). Where a band of the consistent MDSM reaches the
        lowest point of the grid above 0, ``reasons`` says that it may extend below.

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
        consistent, table = unstable_intervals(model, vb=vb, points=points, progress=progress)
    except _Refused as err:
        consistent, reasons["consistent_mdsm"] = None, str(err)
    except RuntimeError as err:
        consistent, reasons["consistent_mdsm"] = None, str(err)
    except ValueError as err:
        # the parameters and the grid are checked above: what is left is the
        # analysis' own limit (one excitation frequency)
        consistent, reasons["consistent_mdsm"] = None, str(err)
    else:
        linear = float(correlation.fast_tangential_velocity(contact=model.contact, **p)[0])
        if linear == 0:
            reasons["consistent_mdsm"] = NO_EXCITATION
        ends = []
        if table["Vb"].size:
            lowest, highest = float(table["Vb"][0]), float(table["Vb"][-1])
            if lowest > 0 and any(lo == lowest for lo, _ in consistent):
                ends.append(GRID_END.format(end="lowest", value=lowest, side="below"))
            if any(hi == highest for _, hi in consistent):
                ends.append(GRID_END.format(end="highest", value=highest, side="above"))
        if ends:
            reasons["consistent_mdsm"] = "; ".join(ends)
        if tension == "clipped":
            reasons["consistent_mdsm"] = "; ".join(
                r for r in (reasons.get("consistent_mdsm"), note) if r
            )
    paper = paper_intervals(model)
    for key, reading in (
        ("paper_tangential_vhat", "tangential"),
        ("paper_coupled_vhat", "coupled"),
    ):
        if paper[reading] is None:
            reasons[key] = NO_VHAT
        elif tension == "clipped":
            reasons[key] = CLIPPED_PAPER
    return Prediction(
        paper["tangential"],
        paper["coupled"],
        consistent,
        reasons,
        tension,
        model.contact,
        model.friction,
    )
