"""The periodic orbit of the normal motion: the orbit the closed-form period map runs on.

Where the normal equation of Eq. (4) does not contain the tangential state (the fact
``one_way_coupling`` of ``beltmdsm.generated.capabilities``), the monodromy matrix of the
response is block triangular, ``[[M_t, M_tn], [0, M_n]]``, and the normal block ``M_n``
belongs to the periodic orbit of the (overdamped) normal motion alone, which depends
only on what the normal equation contains (not on ``Vb``, ``mu_s`` or the tangential
parameters). `normal_orbit` computes it once per normal parameter set (cached), by
shooting on the normal period map with the variational equation (the normal block of
`beltmdsm.generated.hybrid.mode_jacobian`, through the integrator's own steps) and the normal
blocks of the saltation matrices. `beltmdsm.periodic.closed_form` runs on it.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from beltmdsm.generated import dynamics

from ..errors import NoPeriodicResponse
from ..excitation import excitation_period, initial_state
from ..integrate.normal import NormalMotion
from ..model import Model, require
from . import variational
from .base import RTOL
from .newton import NEWTON_TOL

__all__ = [
    "NormalOrbit",
    "normal_orbit",
]

#: Periods the normal motion is followed before Newton's method polishes its orbit.
_NORMAL_PERIODS = 200


@dataclass
class NormalOrbit:
    """The periodic normal motion: ``(X2, X2')`` at phase 0, its monodromy, its switches.

    Attributes
    ----------
    state0 : ndarray (2,)
        ``(X2, X2')`` at phase 0.
    period : float
        The excitation period [s].
    monodromy : ndarray (2, 2)
        The normal block ``M_n`` of the response's monodromy.
    multipliers : ndarray (2,)
        Its eigenvalues: the normal pair of every closed-form `beltmdsm.periodic.floquet.Floquet`.
    switches : list of (t, before, after, surface)
        Contact lost and regained over one period.
    iterations : int
        Newton's iterations that polished it.

    See Also
    --------
    normal_orbit : computes it (cached).

    Examples
    --------
    >>> import numpy as np
    >>> from beltmdsm import Model
    >>> orbit = normal_orbit(Model())
    >>> np.round(orbit.state0, 3), np.round(np.abs(orbit.multipliers), 3), orbit.switches
    (array([12.521,  2.264]), array([0.701, 0.   ]), [])
    """

    state0: np.ndarray
    period: float
    monodromy: np.ndarray
    multipliers: np.ndarray
    switches: list = field(default_factory=list)
    iterations: int = 0


def _normal_flow(model, x0, T):
    """The normal state after ``T``, the monodromy of the normal block and the switches.

    The normal motion of `beltmdsm.integrate.normal.NormalMotion` (the compiled DOP853
    integrator, mode by mode with located switches, the motion the tangential map is
    built on), with its variational equation carried through the same steps
    (`beltmdsm.periodic.variational.propagators`) and the normal block of the saltation
    matrix applied at each switch (the steps next to a touchdown or a lift-off in
    graded pieces, `beltmdsm.periodic.variational.graded_pieces`). Under one-way
    coupling the Jacobians and the saltation matrices are block-triangular: their
    normal blocks, taken at zero tangential state, multiply on their own.
    """
    motion = NormalMotion(model, T, RTOL, RTOL, x0)
    t_steps, h_steps = motion.t_steps, motion.h_steps
    ends = np.minimum(t_steps + h_steps, np.append(t_steps[1:], T))
    contact = [t for t, s in zip(motion.switch_t[1:], motion.switch_surface) if s == "penetration"]
    index, starts, piece_ends = variational.graded_pieces(t_steps, ends, contact)
    # the tangential slots hold z (the response to the contact force): put the
    # tangential state to zero, which the normal block does not read
    y_steps, F_steps = motion.y_steps[index].copy(), motion.F_steps[index].copy()
    y_steps[:, :2] = 0.0
    F_steps[:, :, :2] = 0.0
    segment = np.searchsorted(motion.switch_t, 0.5 * (starts + piece_ends), side="right") - 1
    modes = np.array([float(motion.switch_mode[k]) for k in segment])
    R = variational.propagators(
        model, t_steps[index], h_steps[index], y_steps, F_steps, piece_ends, modes, starts
    )
    # the pieces of each segment, then the saltation of the switch that ends it
    cuts = np.searchsorted(starts, motion.switch_t[1:-1], side="left")
    M, first, switches = np.eye(2), 0, []
    for i, (t, cut) in enumerate(zip(motion.switch_t[1:-1], cuts)):
        for k in range(first, cut):
            M = R[k, 2:, 2:] @ M
        first = cut
        before, after = motion.switch_mode[i], motion.switch_mode[i + 1]
        surface = motion.switch_surface[i]
        state = np.array([0.0, 0.0, *motion.at(t)[2:]])
        S = variational.saltation(model, before, after, surface)(t, *state)
        M = np.array(S).reshape(4, 4)[2:, 2:] @ M
        switches.append((float(t), before, after, surface))
    for k in range(first, starts.size):
        M = R[k, 2:, 2:] @ M
    return motion.at(T)[2:], M, switches


#: The normal orbits of the last parameter sets, by `_normal_orbit_key`.
_NORMAL_ORBITS: dict = {}
_NORMAL_ORBITS_KEPT = 16


def _normal_orbit(model):
    T = excitation_period(model)
    # The normal motion is overdamped: follow it from the equilibrium until it repeats
    # itself to 1e-4 (a few periods; more where it loses contact), then Newton.
    x = initial_state(model)[2:]
    for _ in range(_NORMAL_PERIODS):
        xT, M, switches = _normal_flow(model, x, T)
        close = np.max(np.abs(xT - x)) <= 1e-4 * (1 + np.max(np.abs(x)))
        x = xT
        if close:
            break
    for iteration in range(1, 31):  # noqa: B007 (the count is reported after the loop)
        xT, M, switches = _normal_flow(model, x, T)
        r = xT - x
        if np.max(np.abs(r)) <= NEWTON_TOL * (1 + np.max(np.abs(x))):
            break
        x = x + np.linalg.lstsq(np.eye(2) - M, r, rcond=None)[0]
    else:
        raise NoPeriodicResponse(
            "the normal motion has no periodic orbit: followed from the "
            f"equilibrium for {_NORMAL_PERIODS} periods and then by Newton's "
            "method it does not repeat itself (it loses contact irregularly)"
        )
    xT, M, switches = _normal_flow(model, x, T)
    return NormalOrbit(x, T, M, np.linalg.eigvals(M), switches, iteration)


#: The parameter names of the normal orbit's key by contact and tension law.
_NORMAL_NAMES: dict[tuple[str, str], tuple[str, ...]] = {}


def _normal_orbit_key(model):
    """What the normal orbit depends on: the parameters of the generated normal equation
    and its Jacobian (as the generated code declares them: the names depend on the laws
    only, found once per pair), the period and the laws."""
    laws = tuple(model.options.values())
    names = _NORMAL_NAMES.get(laws)
    if names is None:
        bind_rhs, bind_jac = dynamics.bind_normal_rhs, dynamics.bind_normal_jacobian
        used = bind_rhs(backend="python", **model.arguments(bind_rhs)).params
        used |= bind_jac(backend="python", **model.arguments(bind_jac)).params
        names = _NORMAL_NAMES[laws] = tuple(sorted(used))
    p = model.params
    return (*laws, tuple((k, float(p[k])) for k in names), excitation_period(model))


def normal_orbit(model: Model) -> NormalOrbit:
    """The periodic orbit of the normal motion (cached per normal parameter set).

    The key is what the normal equation contains (the parameters of
    `beltmdsm.generated.dynamics.normal_rhs` and ``normal_jacobian``), the excitation period
    and the laws: a band or a map over ``beta1``, ``omega1``, ``mu_s`` or ``Vb``
    computes one normal orbit.

    Parameters
    ----------
    model : Model

    Returns
    -------
    NormalOrbit
        The same object for models that differ only in what the normal equation
        does not contain.

    Raises
    ------
    beltmdsm.errors.Unsupported
        Where the normal equation is not free of the tangential state (the law).
    beltmdsm.errors.NoPeriodicResponse
        Where the normal motion does not repeat itself (it loses contact irregularly).
    ValueError
        For an excitation without a period.

    See Also
    --------
    beltmdsm.periodic.closed_form.ClosedFormMap : the map that runs on it.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> normal_orbit(Model(Vb=5.0)) is normal_orbit(Model(Vb=9.0, mu_s=0.4))
    True
    >>> normal_orbit(Model(omega2=0.6)) is normal_orbit(Model())
    False
    """
    require(model, "one_way_coupling", "the normal orbit")
    key = _normal_orbit_key(model)
    if key not in _NORMAL_ORBITS:
        if len(_NORMAL_ORBITS) >= _NORMAL_ORBITS_KEPT:
            del _NORMAL_ORBITS[next(iter(_NORMAL_ORBITS))]
        _NORMAL_ORBITS[key] = _normal_orbit(model)
    return _NORMAL_ORBITS[key]
