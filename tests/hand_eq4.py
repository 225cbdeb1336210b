"""Eqs. (1)-(4) typed by hand: the references of test_hybrid, test_tension, test_oscillator.

Nothing here imports the package: every formula is written from the model's definitions
(README, docs/modelling.md, the docstring of derive/hybrid.py), so it is an independent
reference for the generated code. The functions take a module ``m`` for the elementary
functions: ``math`` for floats, ``mpmath`` for a high-precision reference (inputs as
``mpf``). Each value comes with a *scale*, the sum of the absolute values of its terms,
for error models of the form "a few ulps of the terms' scale".
"""

import math

import numpy as np

CONTACTS = ("hertz_damp", "kelvin_voigt")
#: Every law typed here (the CONTACTS above are the runtime's).
ALL_CONTACTS = ("hertz_damp", "kelvin_voigt", "hunt_crossley")
FRICTIONS = ("coulomb", "stribeck", "static_kinetic")
TENSIONS = ("allowed", "clipped")
MODES = {"slip_back": -1, "stick": 0, "slip_forward": 1, "flight": 2, "separated": 3}
EPS = np.finfo(float).eps


def full(p):
    """``p`` with the per-direction excitation filled in (defaults: Eq. 4)."""
    q = dict(p)
    for d in ("t", "n"):
        q.setdefault(f"alpha_{d}", p["alpha"])
        q.setdefault(f"Omega_{d}", p["Omega"])
        q.setdefault(f"phase_{d}", 0.0)
    return q


def excitation(t, p, m=math):
    """``(f_t, f_n)``: ``alpha_t Omega_t^2 sin(Omega_t t + phase_t)``, ``-alpha_n ...``."""
    q = full(p)
    f_t = q["alpha_t"] * q["Omega_t"] ** 2 * m.sin(q["Omega_t"] * t + q["phase_t"])
    f_n = -q["alpha_n"] * q["Omega_n"] ** 2 * m.sin(q["Omega_n"] * t + q["phase_n"])
    return f_t, f_n


def excitation_rate(t, p, m=math):
    """``(f_t', f_n')``."""
    q = full(p)
    return (
        q["alpha_t"] * q["Omega_t"] ** 3 * m.cos(q["Omega_t"] * t + q["phase_t"]),
        -q["alpha_n"] * q["Omega_n"] ** 3 * m.cos(q["Omega_n"] * t + q["phase_n"]),
    )


def excitation_scale(t, p, derivative=0, argument=True):
    """Rounding scale of ``(f_t, f_n)`` (``derivative=1``: of their rates): the
    amplitude times ``|sin| + |theta| |cos|`` with ``theta = Omega t + phase``, because
    the argument itself is rounded (to ``eps |Omega t| + eps |phase|``) before the sine.
    ``argument=False``: the amplitude times ``|sin|``, the absolute value of the term."""
    q = full(p)
    out = []
    for d in ("t", "n"):
        W, ph = q[f"Omega_{d}"], q[f"phase_{d}"]
        theta = W * t + ph
        s, c = abs(math.sin(theta)), abs(math.cos(theta))
        if derivative:
            s, c = c, s
        if not argument:
            c = 0.0
        out.append(q[f"alpha_{d}"] * W ** (2 + derivative) * (s + (abs(W * t) + abs(ph)) * c))
    return tuple(out)


def power(p, contact):
    """The exponent of the penetration: 3/2 (Eq. 1), ``n_h`` (Hunt-Crossley), 1."""
    return {"hertz_damp": 1.5, "hunt_crossley": p.get("n_h", 1.5)}.get(contact, 1)


def force(X2, Y2, p, contact, tension="allowed", extend=False):
    """Eq. (1): Hertz-Damp ``(w2^2 + 2 b2 w2 Y2) X2^(3/2)``, Kelvin-Voigt
    ``w2^2 X2 + 2 b2 w2 Y2``, Hunt-Crossley ``(w2^2 + 2 b2 w2 Y2) X2^n_h``; zero for
    ``X2 <= 0`` unless ``extend`` (the hybrid modes' smooth extension, with
    ``max(X2, 0)`` in place of ``X2``); ``clipped``: ``max(F, 0)``."""
    b2, w2 = p["beta2"], p["omega2"]
    if X2 <= 0 and not extend:
        return 0 * X2
    X = X2 if X2 > 0 else 0 * X2
    if contact == "kelvin_voigt":
        F = w2**2 * X + 2 * b2 * w2 * Y2
    else:
        F = (w2**2 + 2 * b2 * w2 * Y2) * X ** power(p, contact)
    if tension == "clipped" and F < 0:
        return 0 * F
    return F


def force_scale(X2, Y2, p, contact):
    """Sum of the absolute values of the terms of Eq. (1) (in contact)."""
    b2, w2 = p["beta2"], p["omega2"]
    X = max(X2, 0)
    if contact == "kelvin_voigt":
        return w2**2 * X + 2 * b2 * w2 * abs(Y2)
    return (w2**2 + 2 * b2 * w2 * abs(Y2)) * X ** power(p, contact)


def force_gradient(X2, Y2, p, contact, m=math):
    """``(dF/dX2, dF/dY2)`` of Eq. (1) in contact (``X2 > 0``)."""
    b2, w2 = p["beta2"], p["omega2"]
    if contact == "kelvin_voigt":
        return w2**2, 2 * b2 * w2
    n = power(p, contact)
    return n * (w2**2 + 2 * b2 * w2 * Y2) * X2 ** (n - 1), 2 * b2 * w2 * X2**n


def mu(speed, p, friction="coulomb", m=math):
    """The friction coefficient at the sliding speed and its slope: Coulomb's ``mu_s``
    (Eq. 3), Stribeck's ``mu_k + (mu_s - mu_k) exp(-speed/v_s)``, static_kinetic's
    ``mu_k`` while slipping (its static bound ``mu_s`` is the surfaces')."""
    if friction == "coulomb":
        return p["mu_s"], 0 * speed
    if friction == "static_kinetic":
        return p["mu_k"], 0 * speed
    fall = (p["mu_s"] - p["mu_k"]) * m.exp(-speed / p["v_s"])
    return p["mu_k"] + fall, -fall / p["v_s"]


def a_free(t, X1, Y1, p, m=math):
    """Tangential acceleration without friction: ``f_t - 2 b1 w1 Y1 - w1^2 X1``."""
    b1, w1 = p["beta1"], p["omega1"]
    return excitation(t, p, m)[0] - 2 * b1 * w1 * Y1 - w1**2 * X1


def a_free_scale(t, X1, Y1, p, m=math, argument=True):
    b1, w1 = p["beta1"], p["omega1"]
    return excitation_scale(t, p, argument=argument)[0] + 2 * b1 * w1 * abs(Y1) + w1**2 * abs(X1)


def field(mode, t, x, p, contact, m=math, friction="coulomb"):
    """The vector field of a mode (derive/hybrid.py): slip ``s``
    ``(Y1, a_free - mu(s Vr) s F, Y2, g + f_n - F)``; stick ``(Vb, 0, Y2, g + f_n - F)``;
    flight and separated ``(Y1, a_free, Y2, g + f_n)``. ``F`` is the unclipped
    Eq. (1) extended past ``X2 = 0`` with ``max(X2, 0)``."""
    X1, Y1, X2, Y2 = x
    code = MODES.get(mode, mode)
    f_n = excitation(t, p, m)[1]
    a = a_free(t, X1, Y1, p, m)
    F = force(X2, Y2, p, contact, extend=True)
    g = p["g"]
    if code in (-1, 1):
        coefficient = mu(code * (Y1 - p["Vb"]), p, friction, m)[0]
        return [Y1, a - coefficient * code * F, Y2, g + f_n - F]
    if code == 0:
        return [p["Vb"] + 0 * Y1, 0 * Y1, Y2, g + f_n - F]
    return [Y1, a, Y2, g + f_n]


def mode_jacobian(mode, t, x, p, contact, m=math, friction="coulomb"):
    """``d field / d (X1, Y1, X2, Y2)`` of a mode, by hand (the force's derivative in
    ``X2`` taken as 0 at ``X2 <= 0``, where ``max(X2, 0)`` is constant)."""
    X1, Y1, X2, Y2 = x
    code = MODES.get(mode, mode)
    b1, w1 = p["beta1"], p["omega1"]
    zero = 0 * X2
    F = force(X2, Y2, p, contact, extend=True)
    FX, FY = force_gradient(X2, Y2, p, contact, m) if X2 > 0 else (zero, zero)
    if contact == "kelvin_voigt" and X2 <= 0:
        FY = 2 * p["beta2"] * p["omega2"] + zero
    normal = [0, 0, -FX, -FY]
    if code in (-1, 1):
        c, dc = mu(code * (Y1 - p["Vb"]), p, friction, m)
        row = [-(w1**2), -2 * b1 * w1 - dc * F, -c * code * FX, -c * code * FY]
        return [[0, 1, 0, 0], row, [0, 0, 0, 1], normal]
    if code == 0:
        return [[0, 0, 0, 0], [0, 0, 0, 0], [0, 0, 0, 1], normal]
    return [[0, 1, 0, 0], [-(w1**2), -2 * b1 * w1, 0, 0], [0, 0, 0, 1], [0, 0, 0, 0]]


def mode_jacobian_scale(mode, t, x, p, contact, friction="coulomb"):
    """Terms' scale of each entry of `mode_jacobian`."""
    X1, Y1, X2, Y2 = x
    J = mode_jacobian(mode, t, (X1, Y1, X2, abs(Y2)), p, contact, friction=friction)
    F = force_scale(X2, Y2, p, contact)
    code = MODES.get(mode, mode)
    out = [[abs(v) for v in row] for row in J]
    if code in (-1, 1):
        c, dc = mu(code * (Y1 - p["Vb"]), p, friction)
        out[1][1] = 2 * p["beta1"] * p["omega1"] + abs(dc) * F
    return out


def field_scale(mode, t, x, p, contact, m=math, friction="coulomb"):
    """Terms' scale of each entry of `field`."""
    X1, Y1, X2, Y2 = x
    code = MODES.get(mode, mode)
    f_n = excitation_scale(t, p)[1]
    a = a_free_scale(t, X1, Y1, p, m)
    F = force_scale(X2, Y2, p, contact)
    g = p["g"]
    if code in (-1, 1):
        c = mu(code * (Y1 - p["Vb"]), p, friction, m)[0]
        # Stribeck: mu_k plus its fall, each rounded (past the switch the field continues
        # the exponential, which grows there)
        terms = abs(c) if friction == "coulomb" else abs(p["mu_k"]) + abs(c - p["mu_k"])
        return [abs(Y1), a + terms * F, abs(Y2), g + f_n + F]
    if code == 0:
        return [p["Vb"], 0, abs(Y2), g + f_n + F]
    return [abs(Y1), a, abs(Y2), g + f_n]


def surfaces(t, x, p, contact, m=math):
    """The switching functions, in the order of ``SURFACES``: ``Y1 - Vb``,
    ``mu F - a_free``, ``mu F + a_free``, ``X2`` and ``F`` over its factors that are
    positive in contact (Hertz-Damp: ``omega2 X2^(3/2)``; Kelvin-Voigt: ``omega2``)."""
    X1, Y1, X2, Y2 = x
    b2, w2, mu = p["beta2"], p["omega2"], p["mu_s"]
    F = force(X2, Y2, p, contact, extend=True)
    a = a_free(t, X1, Y1, p, m)
    X = X2 if X2 > 0 else 0 * X2
    sign_F = w2 + 2 * b2 * Y2 if contact != "kelvin_voigt" else w2 * X + 2 * b2 * Y2
    return [Y1 - p["Vb"], mu * F - a, mu * F + a, X2, sign_F]


def surface_scales(t, x, p, contact, m=math, argument=True):
    """Rounding scale of each switching function; ``argument=False``: the sum of the
    absolute values of its terms (see `excitation_scale`)."""
    X1, Y1, X2, Y2 = x
    b2, w2, mu = p["beta2"], p["omega2"], p["mu_s"]
    stick = mu * force_scale(X2, Y2, p, contact) + a_free_scale(t, X1, Y1, p, m, argument)
    X = max(X2, 0)
    sign_F = w2 + 2 * b2 * abs(Y2) if contact != "kelvin_voigt" else w2 * X + 2 * b2 * abs(Y2)
    return [abs(Y1) + p["Vb"], stick, stick, abs(X2), sign_F]


def surface_gradients(t, x, p, contact, m=math, absolute=False):
    """``(dh/dt, grad_x h)`` of each switching function, by hand (the force extended
    past ``X2 = 0`` with ``max(X2, 0)``, whose derivative is taken as 0 at ``X2 <= 0``).

    ``absolute=True``: the terms' scale of each entry instead (absolute values of the
    terms), for error bounds.
    """
    X1, Y1, X2, Y2 = x
    if absolute:
        values = surface_gradients(t, (X1, Y1, X2, abs(Y2)), p, contact, m)
        dft = excitation_scale(t, p, derivative=1)[0]
        return [
            (abs(ht) if k not in (1, 2) else dft, [abs(v) for v in n])
            for k, (ht, n) in enumerate(values)
        ]
    b1, w1, b2, w2, mu = (p[k] for k in ("beta1", "omega1", "beta2", "omega2", "mu_s"))
    dft = excitation_rate(t, p, m)[0]
    zero = 0 * X2
    if X2 > 0:
        FX, FY = force_gradient(X2, Y2, p, contact, m)
    else:  # the extension max(X2, 0): Kelvin-Voigt keeps its damping term
        FX, FY = zero, (2 * b2 * w2 if contact == "kelvin_voigt" else zero)
    return [
        (zero, [zero, 1 + zero, zero, zero]),
        (-dft, [w1**2 + zero, 2 * b1 * w1 + zero, mu * FX, mu * FY]),
        (dft, [-(w1**2) + zero, -2 * b1 * w1 + zero, mu * FX, mu * FY]),
        (zero, [zero, zero, 1 + zero, zero]),
        (
            zero,
            [zero, zero, zero, 2 * b2 + zero]
            if contact != "kelvin_voigt"
            else [zero, zero, (w2 if X2 > 0 else 0) + zero, 2 * b2 + zero],
        ),
    ]


def saltation(before, after, surface, t, x, p, contact, m=math):
    """``S = I + (f+ - f-) n^T / (dh/dt + n^T f-)`` (Aizerman-Gantmakher), typed by hand.

    Returns the matrix as nested lists and the rate ``dh/dt + n^T f-``.
    """
    names = ("relative_velocity", "stick_forward", "stick_back", "penetration", "contact_force")
    ht, n = surface_gradients(t, x, p, contact, m)[names.index(surface)]
    fm, fp = field(before, t, x, p, contact, m), field(after, t, x, p, contact, m)
    rate = ht + sum(ni * fi for ni, fi in zip(n, fm))
    S = [[(1 if i == j else 0) + (fp[i] - fm[i]) * n[j] / rate for j in range(4)] for i in range(4)]
    return S, rate


def energy(x, p, contact):
    """Kinetic + spring + contact potential (the integral of Eq. 1's elastic part,
    ``2/5 w2^2 X2^(5/2)`` or ``w2^2 X2^2 / 2``, zero in flight) - gravity ``g X2``."""
    X1, Y1, X2, Y2 = x
    w1, w2, g = p["omega1"], p["omega2"], p["g"]
    X = max(X2, 0)
    n = power(p, contact)
    V = w2**2 * X ** (n + 1) / (n + 1)
    return 0.5 * Y1**2 + 0.5 * Y2**2 + 0.5 * w1**2 * X1**2 + V - g * X2


def rhs(t, x, sgn, p, contact, tension="allowed", m=math):
    """Eq. (4) with friction direction ``sgn`` and Eq. (1)'s force under the tension
    law, zero for ``X2 <= 0``: ``(Y1, a_free - mu sgn F, Y2, g + f_n - F)``."""
    X1, Y1, X2, Y2 = x
    F = force(X2, Y2, p, contact, tension)
    f_n = excitation(t, p, m)[1]
    return [Y1, a_free(t, X1, Y1, p, m) - p["mu_s"] * sgn * F, Y2, p["g"] + f_n - F]


def rhs_scale(t, x, p, contact):
    X1, Y1, X2, Y2 = x
    Fs = force_scale(X2, Y2, p, contact) if X2 > 0 else 0.0
    return [
        abs(Y1),
        a_free_scale(t, X1, Y1, p) + p["mu_s"] * Fs,
        abs(Y2),
        p["g"] + excitation_scale(t, p)[1] + Fs,
    ]


def jacobian(t, x, sgn, p, contact, tension="allowed", m=math):
    """State Jacobian of `rhs` on its branch (contact with the force acting, contact
    with the force clipped to 0, or flight), by hand."""
    X1, Y1, X2, Y2 = x
    b1, w1, mu = p["beta1"], p["omega1"], p["mu_s"]
    FX = FY = 0 * X2
    if X2 > 0 and force(X2, Y2, p, contact, tension) != 0:
        FX, FY = force_gradient(X2, Y2, p, contact, m)
    return [
        [0, 1, 0, 0],
        [-(w1**2), -2 * b1 * w1, -mu * sgn * FX, -mu * sgn * FY],
        [0, 0, 0, 1],
        [0, 0, -FX, -FY],
    ]


def jacobian_scale(t, x, p, contact):
    X1, Y1, X2, Y2 = x
    FX, FY = force_gradient(X2, abs(Y2), p, contact) if X2 > 0 else (0.0, 0.0)
    mu = p["mu_s"]
    return [
        [0, 1, 0, 0],
        [p["omega1"] ** 2, 2 * p["beta1"] * p["omega1"], mu * FX, mu * FY],
        [0, 0, 0, 1],
        [0, 0, FX, FY],
    ]


def power_balance(t, x, sgn, p, contact, tension="allowed", m=math):
    """``(P_input, P_viscous, P_friction)`` per unit mass: the excitation's work rate
    ``f_t Y1 + f_n Y2``; the tangential dashpot ``2 b1 w1 Y1^2`` and the contact force
    beyond its elastic part ``(F_c - F_elastic) Y2`` (in contact); friction
    ``mu sgn F_c Y1``. ``F_c`` is the force under the tension law."""
    X1, Y1, X2, Y2 = x
    f_t, f_n = excitation(t, p, m)
    Fc = force(X2, Y2, p, contact, tension)
    elastic = force(X2, 0 * Y2, p, contact)
    viscous = 2 * p["beta1"] * p["omega1"] * Y1**2 + (Fc - elastic) * Y2
    return f_t * Y1 + f_n * Y2, viscous, p["mu_s"] * sgn * Fc * Y1


def power_scale(t, x, p, contact):
    X1, Y1, X2, Y2 = x
    s_t, s_n = excitation_scale(t, p)
    Fs = force_scale(X2, Y2, p, contact) if X2 > 0 else 0.0
    return (
        s_t * abs(Y1) + s_n * abs(Y2),
        2 * p["beta1"] * p["omega1"] * Y1**2 + 2 * Fs * abs(Y2),
        p["mu_s"] * Fs * abs(Y1),
    )


def energy_scale(x, p, contact):
    X1, Y1, X2, Y2 = x
    w1, w2, g = p["omega1"], p["omega2"], p["g"]
    X = max(X2, 0)
    n = power(p, contact)
    V = w2**2 * X ** (n + 1) / (n + 1)
    return 0.5 * Y1**2 + 0.5 * Y2**2 + 0.5 * w1**2 * X1**2 + V + g * abs(X2)


SURFACE_NAMES = ("relative_velocity", "stick_forward", "stick_back", "penetration", "contact_force")


def rate_scale(mode, t, x, p, contact):
    """Terms' scale of each dh/dt = h_t + n . f along ``mode``: |h_t| + sum |n_i| scale(f_i)."""
    f = field_scale(mode, t, x, p, contact)
    return np.array(
        [
            abs(ht) + sum(abs(ni) * fi for ni, fi in zip(n, f))
            for ht, n in surface_gradients(t, x, p, contact, absolute=True)
        ]
    )


def saltation_scale(before, after, surface, t, x, p, contact, S_ref=None, rate=None):
    """Rounding scale of each entry of S = I + N n^T / r (N = f+ - f-), so that the
    computed S is within a few ulps of it: N_i within ulps of the fields' scales Ns_i,
    r within ulps of its terms' scale R, n_j to a few ulps, and the final addition:
    Ns_i |n_j| / |r| + |N_i n_j| R / r^2 + |S_ij - d_ij| + |S_ij| / 8."""
    if S_ref is None:
        S_ref, rate = saltation(before, after, surface, t, x, p, contact)
    ht, n = surface_gradients(t, x, p, contact, absolute=True)[SURFACE_NAMES.index(surface)]
    Ns = np.add(field_scale(before, t, x, p, contact), field_scale(after, t, x, p, contact))
    fm = field_scale(before, t, x, p, contact)
    R = abs(ht) + sum(abs(ni) * fi for ni, fi in zip(n, fm))
    r = abs(float(rate))
    S = np.abs(np.array(S_ref, dtype=float))
    jump = np.abs(np.array(S_ref, dtype=float) - np.eye(4))
    n = np.abs(np.array(n, dtype=float))
    return np.outer(Ns, n) / r + jump * R / r + jump + S / 8


def response_scale(p, t):
    """Terms' scale of the oscillator's response from rest, z(t) = x_p(t) - Phi(t) x_p(0):
    |x_p| (amplitude alpha_t Omega_t^2 / sqrt(D), D = (w1^2 - W^2)^2 + (2 b1 w1 W)^2,
    times (1, max(W, w1))) twice, times the argument growth (1 + (omega1 + Omega_t) t)."""
    q = full(p) if "alpha" in p else p
    b1, w1, a, W = (q[k] for k in ("beta1", "omega1", "alpha_t", "Omega_t"))
    amp = a * W**2 / np.sqrt((w1**2 - W**2) ** 2 + (2 * b1 * w1 * W) ** 2)
    return 2 * amp * np.array([1.0, max(W, w1)]) * (1 + (w1 + W) * np.max(t))


def response_field(mode, t, y, p, contact, m=math):
    """``(z', z'', X2', Y2')`` of the tangential response ``z`` to the mode's contact
    force beside the normal equation: ``z'' = F_m - 2 b1 w1 z' - w1^2 z``,
    ``Y2' = g + f_n - F_m``, with ``F_m`` the extended Eq. (1) in the contact modes
    (slip_back, stick, slip_forward) and 0 in flight and separation."""
    z, v, X2, Y2 = y
    code = MODES.get(mode, mode)
    Fm = force(X2, Y2, p, contact, extend=True) if code in (-1, 0, 1) else 0 * X2
    f_n = excitation(t, p, m)[1]
    b1, w1 = p["beta1"], p["omega1"]
    return [v, Fm - 2 * b1 * w1 * v - w1**2 * z, Y2, p["g"] + f_n - Fm]


def response_field_scale(mode, t, y, p, contact):
    z, v, X2, Y2 = y
    code = MODES.get(mode, mode)
    Fs = force_scale(X2, Y2, p, contact) if code in (-1, 0, 1) else 0.0
    b1, w1 = p["beta1"], p["omega1"]
    return [
        abs(v),
        Fs + 2 * b1 * w1 * abs(v) + w1**2 * abs(z),
        abs(Y2),
        p["g"] + excitation_scale(t, p)[1] + Fs,
    ]
