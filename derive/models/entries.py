"""The shipped models: ``paper`` (the default), ``belt_1dof`` and ``hoffmann``.

Each is one `register` call; docs/howto/own_model.md adds a model the same way.
"""

from __future__ import annotations

from ..parameters import MODEL, Parameter
from .entry import Contact, Excitation, Oscillator
from .registry import register

__all__: list[str] = []

_ROW = {p.name: p for p in MODEL}


def _rows(*names):
    return tuple(_ROW[n] for n in names)


#: The paper's per-direction excitation (Figs. 14-15; the defaults give Eq. 4).
_PAPER_EXCITATION = (
    Excitation("X1", "alpha_t", "Omega_t", "phase_t"),
    Excitation("X2", "alpha_n", "Omega_n", "phase_n", sign=-1),
)

register(
    "model",
    Oscillator(
        "paper",
        "The paper's 2-DOF mass on a belt: X1 tangential, X2 normal, Hertz-Damp contact",
        "Eq. (4) of the paper, per unit mass: X1'' + 2 beta1 omega1 X1' + omega1^2 X1 = "
        "f_t - mu sgn(Vr) F, X2'' = g + f_n - F, with F the contact law's force on the "
        "penetration X2 (unilateral: the mass flies where X2 < 0) and Vr = X1' - Vb. "
        "The state keeps the paper's order (X1, Y1, X2, Y2). Its own pieces (the cubic "
        "fit, the MDSM, the correlation averages, the paper check) are derived in "
        "derive/ beside it.",
        ("X1", "X2"),
        _rows("beta1", "omega1", "g", "Vb", "alpha_t", "Omega_t", "phase_t")
        + _rows("alpha_n", "Omega_n", "phase_n"),
        Contact(slip=lambda P: {"X1": 1}, normal="X2", law="hertz_damp"),
        damping=lambda P: [[2 * P["beta1"] * P["omega1"], 0], [0, 0]],
        stiffness=lambda P: [[P["omega1"] ** 2, 0], [0, 0]],
        forces=lambda P, q, v, t: {"X2": P["g"]},
        excitation=_PAPER_EXCITATION,
        rates=("Y1", "Y2"),
        states=("X1", "Y1", "X2", "Y2"),
    ),
)

#: The 1-DOF model's excitation: amplitudes default to 0 (the autonomous benchmark).
_BELT_EXCITATION_ROWS = (
    Parameter(
        "alpha_t",
        "m",
        0.0,
        "nonnegative",
        "tangential excitation amplitude (force alpha_t Omega_t^2)",
    ),
    Parameter("Omega_t", "rad/s", 4.0, "nonnegative", "tangential excitation frequency"),
    _ROW["phase_t"],
    Parameter(
        "alpha_n",
        "m",
        0.0,
        "nonnegative",
        "normal load modulation: g - alpha_n Omega_n^2 sin(Omega_n t + phase_n) "
        "(keep alpha_n Omega_n^2 <= g: the load is bilateral and is not clipped)",
    ),
    Parameter("Omega_n", "rad/s", 4.0, "nonnegative", "normal load modulation frequency"),
    _ROW["phase_n"],
)

register(
    "model",
    Oscillator(
        "belt_1dof",
        "The 1-DOF mass on a belt: x'' + 2 beta1 omega1 x' + omega1^2 x = friction + f_t",
        "The field's benchmark (Leine et al. 1998; Thomsen and Fidlin 2003): per unit "
        "mass, x'' + 2 beta1 omega1 x' + omega1^2 x = alpha_t Omega_t^2 sin(Omega_t t + "
        "phase_t) - mu(|v_r|) sgn(v_r) N, v_r = x' - Vb, with the normal load per unit "
        "mass N = g - alpha_n Omega_n^2 sin(Omega_n t + phase_n) (the paper's normal "
        "excitation acting on the load; constant g by default). It is the paper's "
        "model with the normal direction held at its equilibrium (alpha_n = 0 there).",
        ("x",),
        _rows("beta1", "omega1", "g", "Vb") + _BELT_EXCITATION_ROWS,
        Contact(slip=lambda P: {"x": 1}, normal=lambda P, q, v, t: P["g"]),
        damping=lambda P: [[2 * P["beta1"] * P["omega1"]]],
        stiffness=lambda P: [[P["omega1"] ** 2]],
        excitation=(
            Excitation("x", "alpha_t", "Omega_t", "phase_t"),
            Excitation("normal", "alpha_n", "Omega_n", "phase_n", sign=-1),
        ),
    ),
)


def _k(name, base, what):
    return Parameter(name, "N/m", base, "positive", what)


register(
    "model",
    Oscillator(
        "hoffmann",
        "Hoffmann, Fischer and Gaul (2002): the 2-DOF mode-coupling model of brake squeal",
        "Hoffmann, Fischer, Gaul, Mech. Res. Commun. 29 (2002) 197-205, as read here: a "
        "point mass m with coordinates x (along the belt) and y (normal, positive into "
        "the belt), held by a spring k1 along x, a spring k2 along y and a coupling "
        "spring k3 at 45 degrees (stiffness k3/2 [[1, 1], [1, 1]]), dampers c1, c2 "
        "along x and y. The belt touches the mass through a contact spring k_c, "
        "preloaded by F_pre: the normal force is N = k_c y + F_pre (bilateral: the mass "
        "never lifts off; the preload and the contact force's constant part cancel in "
        "the y equation, which keeps -k_c y). Friction mu N acts along x, v_r = x' - Vb: "
        "m x'' + c1 x' + (k1 + k3/2) x + k3/2 y = -mu sgn(v_r) N, "
        "m y'' + c2 y' + k3/2 x + (k2 + k3/2 + k_c) y = 0. Steady sliding couples the "
        "modes through the non-symmetric stiffness mu k_c (the mode-coupling, or "
        "flutter, instability): without damping it is unstable where "
        "mu > ((k1 - k2 - k_c)^2 + k3^2) / (2 k3 k_c).",
        ("x", "y"),
        (
            Parameter("m", "kg", 1.0, "positive", "mass"),
            _k("k1", 1.0, "spring along x"),
            _k("k2", 0.5, "spring along y"),
            _k("k3", 1.0, "coupling spring at 45 degrees"),
            _k("k_c", 1.0, "contact stiffness of the belt"),
            Parameter("F_pre", "N", 1.0, "nonnegative", "normal preload"),
            Parameter("c1", "N s/m", 0.05, "nonnegative", "damper along x"),
            Parameter("c2", "N s/m", 0.05, "nonnegative", "damper along y"),
            _ROW["Vb"],
        ),
        Contact(slip=lambda P: {"x": 1}, normal=lambda P, q, v, t: P["k_c"] * q["y"] + P["F_pre"]),
        mass=lambda P: [[P["m"], 0], [0, P["m"]]],
        damping=lambda P: [[P["c1"], 0], [0, P["c2"]]],
        stiffness=lambda P: [
            [P["k1"] + P["k3"] / 2, P["k3"] / 2],
            [P["k3"] / 2, P["k2"] + P["k3"] / 2 + P["k_c"]],
        ],
    ),
)
