"""Predicted unstable belt speeds: the paper's analysis and a consistent MDSM.

The paper (Sects. 4.2-4.3) linearises the slow equations with the slope ``mu_bar'`` of
Eq. (25); `generated.stability` gives its unstable interval in closed form. The
consistent analysis here keeps what the paper drops (NOTES.md item 3): the
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
"""
from __future__ import annotations

import argparse
import json
from dataclasses import dataclass

import numpy as np
from scipy import optimize

from generated import correlation, stability

from . import intervals
from .parameters import CONTACTS, resolve_parameters

__all__ = ["FastMotion", "fast_motion", "consistent_mdsm_damping", "unstable_intervals",
           "paper_intervals", "predict", "main"]


@dataclass(frozen=True)
class FastMotion:
    """Fast motion at one belt speed: ``v = V sin(Omega t + phi)``, ``N = g + N1 sin(Omega t + psi)``.

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
        raise ValueError("the harmonic balance needs one excitation frequency: "
                         f"Omega_t = {p['Omega_t']} != Omega_n = {p['Omega_n']}")
    return p["Omega_t"]


def _balance(z, p, W, N1, psi, D, Ft):
    """Residual of D V/(i W) = Ft e^{-i phi} - mu_s (s1 + i c1), scaled by |Ft|."""
    V, phi = z
    s1, c1 = correlation.first_harmonic(-p["Vb"], V, p["g"], N1, psi - phi)
    r = D * V / (1j * W) - Ft * np.exp(-1j * phi) + p["mu_s"] * (s1 + 1j * c1)
    return np.array([r.real, r.imag]) / abs(Ft)


def fast_motion(p, contact="hertz_damp", guess=None) -> FastMotion:
    """The fast motion at ``p["Vb"]`` (parameters as `resolve_parameters` returns them).

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
    W = _single_frequency(p)
    N1, psi = (float(x) for x in correlation.fast_normal_force(contact=contact, **p))
    D = p["omega1"]**2 - W**2 + 2j * p["beta1"] * p["omega1"] * W
    Ft = p["alpha_t"] * W**2 * np.exp(1j * p["phase_t"])
    # Friction of constant direction (Vr < 0 throughout): the linear, coupled response.
    V_lin, phi_lin = (float(x) for x in correlation.fast_tangential_velocity(contact=contact,
                                                                            **p))
    if V_lin <= p["Vb"]:
        return FastMotion(V_lin, phi_lin, N1, psi, False, 0.0)
    start = (guess.V, guess.phi) if guess is not None and guess.reverses else (V_lin, phi_lin)
    sol = optimize.root(_balance, start, args=(p, W, N1, psi, D, Ft), method="hybr",
                        options={"xtol": 1e-13})
    V, phi = sol.x
    residual = float(np.max(np.abs(_balance(sol.x, p, W, N1, psi, D, Ft))))
    # hybr may report "not making good progress" once at machine precision: the
    # residual itself is the criterion.
    if residual > 1e-9 or V <= 0:
        raise RuntimeError(f"harmonic balance did not converge at Vb = {p['Vb']}: "
                           f"{sol.message} (residual {residual:.1e})")
    return FastMotion(float(V), float(np.angle(np.exp(1j * phi))), N1, psi, V > p["Vb"],
                      residual)


def consistent_mdsm_damping(p, contact="hertz_damp", fast=None) -> float:
    """Tangential damping ``p = 2 beta1 omega1 + mu_s dF/du`` of the slow motion at ``-Vb``."""
    fast = fast or fast_motion(p, contact)
    slope = correlation.averaged_friction_slope(-p["Vb"], fast.V, p["g"], fast.N1, fast.theta)
    return float(2 * p["beta1"] * p["omega1"] + p["mu_s"] * slope)


def unstable_intervals(params=None, *, contact="hertz_damp", vb=None, **overrides):
    """Unstable belt speeds of the consistent MDSM.

    The damping is evaluated on a grid (continuation from high ``Vb`` down, where the
    fast motion is linear), and each change of sign is refined by bisection
    (``brentq``, to 1e-10 m/s) at a root of the damping; at the onset of friction
    reversal ``V = Vb``, where the slope jumps from an infinite value to zero, the
    edge is the linear amplitude in closed form.

    Returns
    -------
    intervals : list of (lower, upper)
        Unstable ranges of ``Vb`` within the grid (an end of the grid bounds a range
        that reaches it).
    table : dict of arrays
        ``Vb``, ``damping``, ``V``, ``theta``, ``reverses`` on the grid.
    """
    p = resolve_parameters(params, contact=contact, **overrides)
    if vb is None:
        # Above the linear amplitude the friction never reverses and the slope is 0.
        top = 1.05 * float(correlation.fast_tangential_velocity(contact=contact, **p)[0])
        vb = np.linspace(top / 400, top, 400)
    vb = np.asarray(vb, float)
    rows, guess = [], None
    for v in sorted(vb, reverse=True):
        q = {**p, "Vb": float(v)}
        fast = fast_motion(q, contact, guess)
        guess = fast
        rows.append((v, consistent_mdsm_damping(q, contact, fast), fast, ))
    rows.sort(key=lambda r: r[0])
    grid = np.array([r[0] for r in rows])
    damping = np.array([r[1] for r in rows])

    def damping_at(v, guess):
        q = {**p, "Vb": float(v)}
        return consistent_mdsm_damping(q, contact, fast_motion(q, contact, guess))

    cuts = []
    for i in intervals.sign_changes(damping):
        below, above = rows[i][2], rows[i + 1][2]
        if below.reverses != above.reverses:
            # Onset of reversal: at V = Vb the balance is the linear one, so the edge
            # is the linear amplitude itself (independent of Vb); the harmonic balance
            # is singular there and no root-finder is needed.
            cuts.append(above.V if not above.reverses else below.V)
            continue
        cuts.append(optimize.brentq(damping_at, grid[i], grid[i + 1], args=(above,),
                                    xtol=1e-10))
    unstable = intervals.from_crossings(grid, damping < 0, cuts)
    table = {"Vb": grid, "damping": damping,
             "V": np.array([r[2].V for r in rows]),
             "theta": np.array([r[2].theta for r in rows]),
             "reverses": np.array([r[2].reverses for r in rows])}
    return unstable, table


def paper_intervals(params=None, *, contact="hertz_damp", **overrides):
    """The paper's unstable interval ``(Vb_c, Vhat]`` for each ``V_hat`` reading (Eq. 25, 28)."""
    p = resolve_parameters(params, contact=contact, **overrides)
    out = {}
    for model in ("tangential", "coupled"):
        lower, upper = stability.unstable_interval(contact=contact, vhat_model=model, **p)
        out[model] = [(float(lower), float(upper))]
    return out


def predict(params=None, *, contact="hertz_damp", vb=None, **overrides) -> dict:
    """Both analyses' predicted unstable ``Vb`` intervals, as plain data."""
    consistent, _ = unstable_intervals(params, contact=contact, vb=vb, **overrides)
    paper = paper_intervals(params, contact=contact, **overrides)
    return {"paper_tangential_vhat": paper["tangential"],
            "paper_coupled_vhat": paper["coupled"],
            "consistent_mdsm": consistent}


def main(argv=None) -> int:
    """``python -m derive predict [--param value ...] [--json]``."""
    from generated.parameters import PARAMETERS

    parser = argparse.ArgumentParser(prog="python -m derive predict",
                                     description="Predicted unstable belt speeds: the "
                                     "paper's analysis and the consistent MDSM.")
    for q in PARAMETERS:
        if q["name"] not in ("Vb", "Vhat"):
            parser.add_argument(f"--{q['name']}", type=float, default=None,
                                help=f"{q['description']} [{q['unit']}]")
    parser.add_argument("--contact", choices=CONTACTS, default="hertz_damp")
    parser.add_argument("--vb-max", type=float, default=None,
                        help="top of the Vb grid (default: 1.05 x the linear amplitude)")
    parser.add_argument("--vb-points", type=int, default=400)
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args(argv[1:] if argv and argv[0] == "predict" else argv)
    overrides = {q["name"]: getattr(args, q["name"]) for q in PARAMETERS
                 if q["name"] not in ("Vb", "Vhat") and getattr(args, q["name"]) is not None}
    vb = None if args.vb_max is None else np.linspace(args.vb_max / args.vb_points,
                                                       args.vb_max, args.vb_points)
    result = predict(overrides, contact=args.contact, vb=vb)
    if args.json:
        print(json.dumps(result))
        return 0
    for name, found in result.items():
        print(f"{name:>22}: unstable Vb in {intervals.format_intervals(found, '.3f')}")
    return 0



