"""The tangential oscillator of Eq. (4) in closed form.

With the friction direction fixed (a slip mode) or absent (flight), the tangential
equation of Eq. (4),

    X1'' + 2 beta1 omega1 X1' + omega1^2 X1 = f_t(t) - mu_s sgn F(t),

is linear with constant coefficients, so between two switches its solution is a
superposition: the state-transition matrix applied to the state at the switch, plus
the responses from rest to ``f_t`` (a closed form, here) and to the contact force
(which comes from the normal motion and is integrated numerically by the runtime).

`state_transition` is ``expm(A tau)`` for ``A = [[0, 1], [-omega1^2, -2 beta1 omega1]]``
written as ``e^(a tau) (C I + S (A - a I))`` with ``a = -beta1 omega1`` and
``C = cosh(b tau)``, ``S = sinh(b tau) / b``, ``b^2 = a^2 - omega1^2`` (Cayley-Hamilton).
Each damping regime gets the form that stays accurate: under-damped ``cos``/``sin``;
over-damped exponentials through ``expm1`` (no overflow for long ``tau``, no
cancellation as ``b -> 0``); critically damped (``beta1 = 1`` exactly) ``C = 1``,
``S = tau``. `verify_state_transition` proves with SymPy that each form solves
``Phi' = A Phi``, ``Phi(0) = I``.

`tangential_state` is the superposition itself, the one formula of the tangential
motion between switches that the runtime evaluates (the superposition integrator, the
sliding orbit of the period map):

    x(t) = Phi(t - t0) (x(t0) - f(t0)) + f(t),    f = zf - mu sgn z,

with ``zf`` the excitation response, ``z`` the response to the contact force ``F``
(both from rest at ``t = 0``), ``sgn`` the friction direction of the mode (0 in flight
or separation) and ``mu`` the friction law's coefficient, constant within a slip mode
where the law's friction does not depend on the sliding speed (Coulomb's ``mu_s``).
`verify_tangential_state` proves that it solves the tangential equation with
``x(t0)`` as its start.
"""

from __future__ import annotations

import sympy as sp
from sympy.codegen.cfunctions import expm1

from .model import SPEED, P, coefficient, excitation, t

__all__ = [
    "tau",
    "system_matrix",
    "state_transition",
    "state_transition_branches",
    "verify_state_transition",
    "harmonic_steady_state",
    "excitation_response",
    "SUPERPOSITION_ARGS",
    "tangential_state",
    "verify_tangential_state",
]

#: Time elapsed since the switch.
tau = sp.Symbol("tau", nonnegative=True)


def system_matrix() -> sp.Matrix:
    """``A`` of the first-order tangential oscillator ``(X1, X1')' = A (X1, X1')``."""
    return sp.Matrix([[0, 1], [-(P["omega1"] ** 2), -2 * P["beta1"] * P["omega1"]]])


def state_transition_branches() -> dict[str, sp.Matrix]:
    """``expm(A tau)`` in each damping regime: under-, over- and critically damped."""
    b1, w1 = P["beta1"], P["omega1"]
    A = system_matrix()
    a = -b1 * w1
    shifted = A - a * sp.eye(2)
    under_b = w1 * sp.sqrt((1 - b1) * (1 + b1))
    over_b = w1 * sp.sqrt((b1 - 1) * (b1 + 1))
    # e^(a tau) cosh(b tau) and e^(a tau) sinh(b tau)/b through e^((a + b) tau) <= 1
    # and expm1(-2 b tau): bounded for long tau, accurate as b tau -> 0. The slow rate
    # a + b = -omega1 (beta1 - sqrt(beta1^2 - 1)) is written without the cancellation
    # of its two terms (they agree to 1/(2 beta1^2) for strong damping).
    slow = sp.exp(-w1 / (b1 + sp.sqrt((b1 - 1) * (b1 + 1))) * tau)
    decay = -expm1(-2 * over_b * tau)
    forms = {
        "under": (
            sp.exp(a * tau) * sp.cos(under_b * tau),
            sp.exp(a * tau) * sp.sin(under_b * tau) / under_b,
        ),
        "over": (slow * (1 - decay / 2), slow * decay / (2 * over_b)),
        "critical": (sp.exp(a * tau), tau * sp.exp(a * tau)),
    }
    return {name: C * sp.eye(2) + S * shifted for name, (C, S) in forms.items()}


def state_transition() -> sp.Matrix:
    """``Phi(tau) = expm(A tau)``, one Piecewise over the damping regime per entry."""
    b1 = P["beta1"]
    forms = state_transition_branches()
    return sp.Matrix(
        2,
        2,
        lambda i, j: sp.Piecewise(
            (forms["under"][i, j], b1 < 1),
            (forms["over"][i, j], b1 > 1),
            (forms["critical"][i, j], True),
        ),
    )


def verify_state_transition() -> None:
    """Prove that each regime's form is the state-transition matrix.

    ``Phi(0) = I`` and ``Phi' - A Phi = 0`` identically, on the parameter range of
    the regime (``beta1 = 1`` for the critical form).

    Raises
    ------
    AssertionError
        Naming the regime whose form fails.
    """
    A = system_matrix()
    b1 = P["beta1"]
    for name, Phi in state_transition_branches().items():
        if name == "critical":
            Phi, A_r = Phi.subs(b1, 1), A.subs(b1, 1)
        else:
            A_r = A
        residual = (sp.diff(Phi, tau) - A_r * Phi).applyfunc(
            lambda e: sp.simplify(sp.expand(e.rewrite(sp.exp)))
        )
        start = Phi.subs(tau, 0).applyfunc(sp.simplify)
        if not residual.is_zero_matrix or start != sp.eye(2):
            raise AssertionError(
                f"{name}-damped state-transition matrix fails: "
                f"residual {residual}, Phi(0) = {start}"
            )


def harmonic_steady_state() -> sp.Matrix:
    """The periodic response ``(X1, X1')`` of the free oscillator to ``f_t`` (Eq. 4).

    ``X1 = A_s sin(Omega_t t + phase_t) + A_c cos(Omega_t t + phase_t)``, the
    amplitudes solved by SymPy from the oscillator equation. It does not exist at
    undamped resonance (``beta1 = 0``, ``Omega_t = omega1``): the expressions divide
    by zero there.
    """
    b1, w1 = P["beta1"], P["omega1"]
    W, ph = P["Omega_t"], P["phase_t"]
    As, Ac = sp.symbols("A_s A_c")
    x = As * sp.sin(W * t + ph) + Ac * sp.cos(W * t + ph)
    residual = sp.expand(
        sp.diff(x, t, 2) + 2 * b1 * w1 * sp.diff(x, t) + w1**2 * x - excitation()[0]
    )
    eqs = [residual.coeff(sp.sin(W * t + ph)), residual.coeff(sp.cos(W * t + ph))]
    sol = sp.solve(eqs, [As, Ac], dict=True)[0]
    # |omega1^2 - Omega_t^2 + 2i beta1 omega1 Omega_t|^2 as a sum of squares: expanded,
    # it cancels next to resonance
    D = (w1**2 - W**2) ** 2 + (2 * b1 * w1 * W) ** 2
    sol = {k: sp.factor_terms(v.subs(sp.expand(D), D)) for k, v in sol.items()}
    assert all(
        sp.expand(sp.denom(v) - D) == 0 or sp.expand(sp.denom(v) + D) == 0 for v in sol.values()
    ), sol
    x = x.subs(sol)
    return sp.Matrix([sp.factor_terms(x), sp.factor_terms(sp.diff(x, t))])


def excitation_response() -> sp.Matrix:
    """``(X1, X1')`` of the oscillator driven by ``f_t`` from rest at ``t = 0``.

    The steady state minus the free response that cancels its initial value:
    ``z_f(t) = x_p(t) - Phi(t) x_p(0)``.
    """
    xp = harmonic_steady_state()
    return xp - state_transition().subs(tau, t) * xp.subs(t, 0)


#: The friction direction of a mode: -1 or +1 slipping, 0 in flight or separation.
sgn = sp.Symbol("sgn", real=True)
#: The arguments of `tangential_state` after ``tau``: the state at the switch, the
#: excitation response ``(zf, zf')`` and the response to the contact force ``(z, z')``
#: there, the same two responses at ``t0 + tau``, and the friction direction.
SUPERPOSITION_ARGS = (
    *sp.symbols("X1_0 Y1_0 zf_0 vf_0 z_0 v_0 zf vf z v", real=True),
    sgn,
)


def _forced(mu, zf, vf, z, v) -> sp.Matrix:
    """``f = zf - mu sgn z``: the forced part of the motion of a mode."""
    return sp.Matrix([zf - mu * sgn * z, vf - mu * sgn * v])


def tangential_state(friction: str = "coulomb") -> sp.Matrix | None:
    """``(X1, X1')`` at ``t0 + tau`` of a mode entered at ``t0`` (module docstring).

    ``Phi(tau) (x0 - f0) + f`` in the arguments `SUPERPOSITION_ARGS`, one Piecewise over
    the damping regime per entry (as `state_transition`). None where the friction law's
    coefficient depends on the sliding speed: the friction of a slip mode then depends
    on ``X1'`` and the motion is no superposition.
    """
    mu = coefficient(friction, SPEED)
    if SPEED in mu.free_symbols:
        return None
    X10, Y10, zf0, vf0, z0, v0, zf, vf, z, v, _ = SUPERPOSITION_ARGS
    free = sp.Matrix([X10, Y10]) - _forced(mu, zf0, vf0, z0, v0)
    forced = _forced(mu, zf, vf, z, v)
    forms = {name: Phi * free + forced for name, Phi in state_transition_branches().items()}
    b1 = P["beta1"]
    return sp.Matrix(
        [
            sp.Piecewise(
                (forms["under"][i], b1 < 1),
                (forms["over"][i], b1 > 1),
                (forms["critical"][i], True),
            )
            for i in range(2)
        ]
    )


def verify_tangential_state(friction: str = "coulomb") -> None:
    """Prove that `tangential_state` is the motion of the mode from ``x(t0)``.

    With ``Phi`` any matrix with ``Phi' = A Phi`` and ``Phi(0) = I``
    (`verify_state_transition`), ``zf' = vf``, ``vf' = f_t - 2 beta1 omega1 vf -
    omega1^2 zf`` and ``z' = v``, ``v' = F - 2 beta1 omega1 v - omega1^2 z``, the
    superposition ``x = Phi (x0 - f0) + f`` has ``x(t0) = x0`` and
    ``x' = A x + (0, f_t - mu sgn F)``: the tangential equation of Eq. (4) in a mode
    with friction direction ``sgn`` (derive/model.py).

    Raises
    ------
    AssertionError
        Naming what fails.
    """
    mu = coefficient(friction, SPEED)
    assert SPEED not in mu.free_symbols, f"friction={friction!r}: no superposition"
    X10, Y10, zf0, vf0, z0, v0, zf, vf, z, v, _ = SUPERPOSITION_ARGS
    A = system_matrix()
    Phi = sp.Matrix(2, 2, sp.symbols("p0:4"))
    f_t, F = excitation()[0], sp.Symbol("F", real=True)
    free = sp.Matrix([X10, Y10]) - _forced(mu, zf0, vf0, z0, v0)
    x = Phi * free + _forced(mu, zf, vf, z, v)
    # d/dt along the responses' own equations, and Phi' = A Phi
    rates = {
        zf: vf,
        vf: f_t + A[1, 0] * zf + A[1, 1] * vf,
        z: v,
        v: F + A[1, 0] * z + A[1, 1] * v,
    }
    dPhi = A * Phi
    dx = x.applyfunc(
        lambda e: (
            sum(sp.diff(e, s) * r for s, r in rates.items())
            + sum(sp.diff(e, Phi[k]) * dPhi[k] for k in range(4))
        )
    )
    residual = (dx - A * x - sp.Matrix([0, f_t - mu * sgn * F])).applyfunc(sp.expand)
    if not residual.is_zero_matrix:
        raise AssertionError(f"tangential_state does not solve Eq. (4): residual {residual}")
    at_start = x.subs(dict(zip(Phi, sp.eye(2)))).subs({zf: zf0, vf: vf0, z: z0, v: v0})
    if (at_start - sp.Matrix([X10, Y10])).applyfunc(sp.expand) != sp.zeros(2, 1):
        raise AssertionError(f"tangential_state at tau = 0 is {at_start.T}, not (X1_0, Y1_0)")
