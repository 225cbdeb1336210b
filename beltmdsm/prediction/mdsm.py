"""The consistent MDSM at one belt speed: the fast motion and the slow damping.

The paper (Sects. 4.2-4.3) linearises the slow equations with the slope ``mu_bar'`` of
Eq. (25) (`beltmdsm.prediction.paper`). The consistent analysis keeps what the paper
drops (docs/modelling.md#averaging): the correlation between the fast friction
direction and the fast normal force. It follows the model's laws (``friction=``,
``contact=``; `Model.arguments` hands each generated function the options it
declares) and computes with no other law's physics. For a belt speed ``Vb`` it

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
   nonlinear system, solved by Newton iterations continued in ``Vb`` (`fast_motion`);
3. linearises the averaged friction ``<mu(|v|) sgn(v) N>`` in the slow velocity at
   frozen fast amplitude and phase: the tangential damping is
   `beltmdsm.generated.correlation.slow_damping`, ``2 beta1 omega1 + d<...>/du`` (for
   Coulomb's law ``2 beta1 omega1 + mu_s dF/du``), unstable when negative (the normal
   block is that of Eq. 22 and always stable; `consistent_mdsm_damping`). For a law
   without a closed-form fast average (Stribeck's) the averages are quadratures of
   the same expression.

Only one excitation frequency is covered (``Omega_t == Omega_n``): with two frequencies
a single harmonic balance does not apply and `fast_motion` raises. The scan of this
damping over ``Vb`` is `beltmdsm.prediction.scan`.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import optimize

from beltmdsm.generated import correlation, unforced

from ..model import Model, require

__all__ = [
    "FastMotion",
    "fast_motion",
    "consistent_mdsm_damping",
    "reversal_onset",
    "clip_acts",
]


@dataclass(frozen=True)
class FastMotion:
    """Fast motion at one belt speed.

    ``v = V sin(Omega t + phi)``, ``N = g + N1 sin(Omega t + psi)``.

    Parameters
    ----------
    V, phi : float
        Amplitude [m/s] and phase [rad] of the fast relative velocity.
    N1, psi : float
        Amplitude [m/s^2, per unit mass] and phase [rad] of the fast normal force.
    reverses : bool
        True when the friction changes direction within a fast cycle (``V > Vb``).
    residual : float
        The relative residual of the harmonic balance (0 for the linear solution).

    Attributes
    ----------
    theta : float
        ``psi - phi``, the phase of the normal force ahead of the velocity.

    See Also
    --------
    fast_motion : what finds it.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> fast = fast_motion(Model(Vb=5.0))
    >>> round(fast.V, 4), fast.reverses, round(fast.theta, 4)
    (6.6571, True, 3.8977)
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
    model : Model
        The parameters and the laws (one excitation frequency, ``Omega_t == Omega_n``).
    guess : FastMotion, optional
        Start of the Newton iterations (continuation from a neighbouring ``Vb``), whose
        kind (reversing or not) is tried first; default: the linear solution, and the
        solution without reversal first (the one Coulomb's law has wherever it exists).

    Returns
    -------
    FastMotion
        The linear response where the friction does not reverse and its coefficient is
        constant in slip; else the solution of the harmonic balance.

    Raises
    ------
    RuntimeError
        If the harmonic balance does not converge.
    ValueError
        Two excitation frequencies, or laws whose normal motion depends on the
        tangential one (`beltmdsm.model.Unsupported`, naming the law).

    See Also
    --------
    consistent_mdsm_damping : the slow damping at this fast motion.
    reversal_onset : the belt speed where the friction starts to reverse.

    Examples
    --------
    Below the onset of reversal (6.375 m/s at the base set) the friction reverses
    within a fast cycle, above it not:

    >>> from beltmdsm import Model
    >>> [fast_motion(Model(Vb=vb)).reverses for vb in (5.0, 8.0)]
    [True, False]
    >>> fast_motion(Model(Vb=5.0, Omega_n=7.0))
    Traceback (most recent call last):
    ...
    ValueError: the harmonic balance needs one excitation frequency: Omega_t = 4.0 != Omega_n = 7.0
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

    Parameters
    ----------
    model : Model
        The parameters and the laws.
    fast : FastMotion, optional
        The fast motion at the model's ``Vb`` (default: `fast_motion` of the model).

    Returns
    -------
    float
        The damping [1/s]; steady sliding is unstable in the consistent MDSM where it
        is negative.

    Raises
    ------
    ValueError, RuntimeError
        Those of `fast_motion`, where ``fast`` is not given.

    See Also
    --------
    beltmdsm.prediction.scan.unstable_intervals : its sign over a grid of ``Vb``.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> round(consistent_mdsm_damping(Model(Vb=5.0)), 4)  # unstable
    -0.0918
    >>> round(consistent_mdsm_damping(Model(Vb=8.0)), 4)  # 2 beta1 omega1: stable
    0.2
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

    Parameters
    ----------
    model : Model
        The parameters and the laws (its ``Vb`` is not used).
    start : float, optional
        The belt speed to start the iterations from.

    Returns
    -------
    float
        The belt speed [m/s] where ``V(Vb) = Vb``.

    Raises
    ------
    RuntimeError
        If the balance does not converge (naming the belt speed it started from).

    See Also
    --------
    fast_motion : the fast motion at one belt speed.

    Examples
    --------
    For Coulomb's law the onset is the linear amplitude, the upper end of the
    consistent MDSM's band at the base set:

    >>> from beltmdsm import Model
    >>> round(reversal_onset(Model()), 4)
    6.3754
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


def clip_acts(model: Model) -> tuple[bool, float]:
    """``(acts, N1)``: whether the clip cuts the linear fast normal force ``g + N1 sin``.

    Parameters
    ----------
    model : Model
        The parameters and the laws.

    Returns
    -------
    acts : bool
        True when ``N1 >= g`` (the force would reach zero within a fast cycle).
    N1 : float
        The amplitude from `beltmdsm.generated.correlation.fast_normal_force`.

    See Also
    --------
    beltmdsm.prediction.prediction.predict : no consistent MDSM where the clip acts.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> acts, N1 = clip_acts(Model())
    >>> acts, round(N1, 2)
    (True, 27.17)
    """
    N1 = _normal(model)[0]
    return N1 >= model["g"], N1
