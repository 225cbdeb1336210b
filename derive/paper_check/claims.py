"""The paper's claims in words, each re-derived: holds, holds under a reading, or does not.

Each `Claim` has a check that returns the readings under which it holds and one line of
evidence computed from the derivation, and a statement of the friction laws it holds
for (the paper's model has Coulomb's law; `beltmdsm.derive.laws` has more). Two claims also need
the simulation of Eq. (4): its numbers come in as ``evidence``, a function that returns
them per tension law (``beltmdsm.paper_reports.contraction_evidence.paper_evidence``,
handed over by the command line, ``python -m derive check-paper``: derive/ never imports
the runtime). Without it those two claims say that they were not checked.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import mpmath
import sympy as sp

from .. import contraction, friction, laws, mdsm, paper, stability, statespace
from ..fit import X2max, fit_error
from ..model import BASE, P, equal_excitation, lam
from .engine import CONVENTIONS, d

__all__ = ["Claim", "ClaimResult", "claims", "check_claim", "base_numbers"]

_PAPER_LAW = f"{laws.default('friction')} (the paper's law)"


@dataclass(frozen=True)
class Claim:
    """A statement of the paper in words, with the function that checks it.

    ``check`` returns ``(holds_under, evidence)``: the readings under which the
    claim holds (``["" ]`` when it holds without a reading, ``[]`` when it does not)
    and one line of evidence computed from the derivation. ``laws`` returns the
    friction laws the claim holds for, in words (default: the paper's law only, the
    one it was derived for).
    """

    key: str
    where: str
    text: str
    readings: tuple[str, ...]
    check: Callable[[], tuple[list[str], str]]
    laws: Callable[[], str] = lambda: _PAPER_LAW


@dataclass(frozen=True)
class ClaimResult:
    claim: Claim
    status: str
    evidence: str
    laws: str


def base_numbers() -> dict:
    num = {P[k]: sp.nsimplify(v) for k, v in BASE.items() if k in P}
    num.update({k: sp.sympify(v).subs(num) for k, v in equal_excitation().items()})
    return num


def _n(expr, digits=6):
    return sp.N(expr, digits)


def _claim_mu_s():
    J0 = statespace.jacobian_at_equilibrium_eq_11()
    poly = statespace.charpoly_eq_12(J0).as_expr()
    in_J = not statespace.free_of(J0, P["mu_s"])
    absent = statespace.free_of(poly, P["mu_s"]) and statespace.free_of(paper.eq_12(), P["mu_s"])
    ok = in_J and absent
    return ([""] if ok else []), (
        f"`mu_s` {'appears' if in_J else 'does not appear'} in `J^0` (Eq. 11) and "
        f"{'is absent from' if absent else 'appears in'} `det(lambda I - J^0)` "
        "(derived and printed): the friction column only couples the tangential block "
        "to the normal one, so the determinant is the product of the two diagonal blocks."
    )


def _laws_mu_s() -> str:
    """For which friction laws ``mu_s`` is absent from ``det(lambda I - J^0)``."""
    out = []
    for law in laws.choices("friction"):
        poly = statespace.charpoly_eq_12(statespace.jacobian_at_equilibrium_eq_11(friction=law))
        out.append((law, statespace.free_of(poly.as_expr(), P["mu_s"])))
    free = [law for law, ok in out if ok]
    rest = [
        f"{law}: mu_s enters through the slope mu'(Vb) in the tangential damping"
        for law, ok in out
        if not ok
    ]
    return ", ".join(free) + (" only (" + "; ".join(rest) + ")" if rest else " (every law)")


def _laws_only_slope() -> str:
    return (
        "every law: a1..a4 are derived in mu_bar^0, mu_bar' (beltmdsm.derive.stability), whatever "
        "law mu_bar averages"
    )


def _laws_contraction() -> str:
    parts = []
    for law in laws.choices("friction"):
        m = contraction.claim(law).monotone
        parts.append(f"{law}: {'proved' if m.holds else 'NOT proved'} ({m.reason})")
    return "; ".join(parts)


def _claim_only_slope():
    found = []
    for c in CONVENTIONS:
        a = stability.coefficients_A8(c)
        found.append(
            all(statespace.free_of(x, stability.mu0) for x in a)
            and any(not statespace.free_of(x, stability.mu1) for x in a)
        )
    printed = paper.eq_A8()
    found.append(
        printed.free_symbols.isdisjoint({stability.mu0}) and stability.mu1 in printed.free_symbols
    )
    ok = all(found)
    return ([""] if ok else []), (
        "`a1..a4` contain `mu_bar'` and not `mu_bar^0` in both conventions and in the "
        "printed Eq. A8: `mu_bar^0` sits only in the upper-right block of `J_f^0`, "
        "which a block-triangular determinant never uses."
    )


def _claim_fit():
    err = fit_error(3)
    rel = err.max_abs / X2max ** sp.Rational(3, 2)
    num = base_numbers()
    top = mdsm.x2max().subs(num)
    absolute = err.max_abs.subs(X2max, top)
    order = lambda v: round(float(sp.log(sp.N(v, 30), 10)))  # noqa: E731
    holds = []
    if order(rel) == -2:
        holds.append("relative to X2max^(3/2)")
    if order(absolute) == -2:
        holds.append("absolute, base set")
    return holds, (
        f"largest error exactly `{sp.sstr(err.max_abs)}` at `X2 = {sp.sstr(err.argmax)}` "
        f"(RMS `{sp.sstr(err.rms)}`): {_n(rel, 3)} of `X2max^(3/2)`, which rounds to "
        f'1e{order(rel)} ("about 1e-2" read as the nearest power of ten); in absolute '
        f"terms at the base set's fitted range `X2max = {_n(top, 4)}` m "
        f"(`beltmdsm.derive.mdsm.x2max`) it is {_n(absolute, 3)} m^(3/2)."
    )


def _claim_overdamped():
    num = base_numbers()
    normal = statespace.block_quadratics(statespace.jacobian_at_equilibrium_eq_11())[1]
    disc = normal.disc.subs(num)
    same = all(
        stability.forced_jacobian_eq_22(c)[2:, 2:]
        == statespace.jacobian_at_equilibrium_eq_11()[2:, 2:]
        for c in CONVENTIONS
    )
    b2 = P["beta2"]
    crit = [
        r
        for r in sp.solve(normal.disc.subs({k: v for k, v in num.items() if k != b2}), b2)
        if r.is_positive
    ]
    ok = disc > 0 and normal.p.subs(num) > 0 and normal.q.subs(num) > 0 and same
    return ([""] if ok else []), (
        f"normal block of `J^0`: `lambda^2 + {_n(normal.p.subs(num), 4)} lambda + "
        f"{_n(normal.q.subs(num), 4)}`, quarter discriminant {_n(disc, 4)} > 0 (two real "
        f"negative eigenvalues); the forced `J_f^0` has the same normal block "
        f"({'both conventions' if same else 'NOT in every convention'}); critical damping "
        f"at `beta2* = {', '.join(str(_n(r, 4)) for r in crit)}`."
    )


def _unstable_ranges(convention: str, vhat_value, num) -> list[tuple[float, float]]:
    """Belt speeds in [0, 20] where a Hurwitz determinant of the derived quartic is <= 0.

    Scanned on a 0.05 m/s grid, each edge then bisected to 1e-15.
    """
    a = [
        stability.with_friction(x).subs(num).subs(P["Vhat"], vhat_value)
        for x in stability.coefficients_A8(convention)
    ]
    H = [sp.lambdify(P["Vb"], h, "mpmath") for h in stability.hurwitz_determinants(*a)]

    def unstable(v):
        return any(h(v) <= 0 for h in H)

    with mpmath.workdps(30):
        grid = [mpmath.mpf(k) / 20 for k in range(0, 401)]
        flags = [unstable(v) for v in grid]
        edges = []
        for (v0, f0), (v1, f1) in zip(zip(grid, flags), zip(grid[1:], flags[1:])):
            if f0 != f1:
                lo, hi = v0, v1
                for _ in range(50):
                    mid = (lo + hi) / 2
                    lo, hi = (mid, hi) if unstable(mid) == f0 else (lo, mid)
                edges.append(float(hi))
    bounds = ([0.0] if flags[0] else []) + edges + ([20.0] if flags[-1] else [])
    return list(zip(bounds[::2], bounds[1::2]))


def _claim_bifurcation():
    num = {k: v for k, v in base_numbers().items() if k != P["Vb"]}
    holds, parts = [], []
    for model in friction.VHAT_MODELS:
        vh = sp.N(friction.vhat(model).subs(num), 30)
        vh = sp.re(vh) if abs(sp.im(vh)) < 1e-20 else vh
        for c in CONVENTIONS:
            ranges = _unstable_ranges(c, vh, num)
            text = ", ".join(f"[{lo:.4g}, {hi:.4g})" for lo, hi in ranges) if ranges else "none"
            parts.append(f"V_hat {model} ({_n(vh, 4)}), {c}: unstable {text}")
            if ranges and abs(ranges[-1][1] - 8) <= 0.8:
                holds.append(f"V_hat {model}, convention {c}")
    return holds, (
        "; ".join(parts) + '. "About 8" read as within 10 %: the upper end '
        "of the unstable range (stable above it) must lie in [7.2, 8.8]."
    )


def _claim_slope():
    Vb, Vh, mu = P["Vb"], P["Vhat"], P["mu_s"]
    slope = friction.mu_bar_slope_eq_25()
    below = slope.args[0][0]
    rising = sp.simplify(sp.diff(below, Vb).subs(Vh, Vb + d)).is_nonnegative
    # One-sided limit through Vb = Vhat - e, e -> 0+ (SymPy's limit at the symbolic
    # point Vhat with dir="-" returns -oo), for mu_s > 0 (mu_s = 0: no friction).
    e, m = sp.Symbol("e", positive=True), sp.Symbol("m", positive=True)
    to_inf = sp.limit(below.subs({Vb: Vh - e, mu: m}), e, 0, "+") == sp.oo
    above = slope.subs({Vh: 1, Vb: 2}) == 0
    start = below.subs(Vb, 0)
    num = base_numbers()
    vh = sp.N(friction.vhat("tangential").subs(num), 15)
    ok = bool(rising and to_inf and above)
    return ([""] if ok else []), (
        f"for `Vb < Vhat` the slope {'rises' if rising else 'does NOT rise'} with `Vb` "
        f"(derivative >= 0), {'tends to +oo' if to_inf else 'stays finite'} as "
        f"`Vb -> Vhat-`, and is {'0' if above else 'not 0'} for `Vb > Vhat`; its smallest "
        f"value is `{sp.sstr(start)}` at `Vb = 0`, {_n(start.subs(num).subs(Vh, vh), 3)} at "
        'the base set (tangential `Vhat`): "nearly zero" only for large `Vhat`.'
    )


def _claim_unforced_limit():
    poly = statespace.charpoly_eq_12(statespace.jacobian_at_equilibrium_eq_11())
    ok = all(
        sp.expand(
            sp.Poly(
                statespace.charpoly_eq_12(stability.forced_jacobian_eq_22(c))
                .as_expr()
                .subs(stability.mu1, 0),
                lam,
            ).as_expr()
            - poly.as_expr()
        )
        == 0
        for c in CONVENTIONS
    )
    return ([""] if ok else []), (
        "with `mu_bar' = 0` the derived quartic of `J_f^0` equals `det(lambda I - J^0)` "
        f"in both conventions: {'yes' if ok else 'NO'}."
    )


def _claim_state_space():
    """Eq. (A4) against the printed Eq. (20) moved to state-space form."""
    z = mdsm
    to_state = {
        sp.diff(z.Z1, z.tau, 2): sp.Symbol("S1dot"),
        sp.diff(z.Z1, z.tau): stability.S1,
        sp.diff(z.Z2, z.tau): stability.S2,
    }
    eq20 = paper.eq_20().subs(to_state).subs({z.Z1: stability.Z1, z.Z2: stability.Z2})
    eq20 = eq20.subs(z.mu_bar, stability.mu_bar(stability.S1 - P["Vb"]))
    s1dot = sp.solve(eq20, sp.Symbol("S1dot"))[0]
    diff = sp.factor(sp.expand(paper.eq_A4() - s1dot))
    ok = diff == 0
    return ([""] if ok else []), (
        "Eq. (20) as printed, solved for `S1'`, minus Eq. (A4) as printed: "
        f"`{sp.sstr(-diff)}`"
        + (
            ""
            if ok
            else " - the friction term has opposite signs; A4 agrees "
            "with Eq. 20 only if its `mu_bar` is read as `-mu_bar`"
            " (the sign resolved for `V_r < 0`, as `+mu_s` in Eq. 6)."
        )
    )


#: E_d "never rises" when no step between samples exceeds this fraction of E_d(0) (the
#: runs' tolerance is 1e-10; tests/beltmdsm/paper_reports/test_contraction_evidence.py
#: bounds it finer).
RISE_TOLERANCE = 1e-9
#: E_d has "decayed" below this fraction of E_d(0) at the end of a run.
DECAYED = 1e-12
_NOT_CHECKED = (
    "not checked: the simulation of Eq. (4) is needed (run `python -m derive check-paper` "
    "with the runtime, beltmdsm, installed)"
)


def _shift_text(e) -> str:
    return "(" + ", ".join(f"{x:g}" for x in e.shift) + ")"


def _ratio_text(r) -> str:
    return f"= {r:.2f}" if r >= 1e-2 else ("< 1e-4" if r < 1e-4 else f"= {r:.1g}")


def _omega1_peak(evidence):
    """The claim row "omega1 peak (Fig. 2b)" on the simulated evidence."""
    holds, parts = [], []
    for tension in ("allowed", "clipped"):
        e = evidence[tension]
        free_phase = e.energy_end > DECAYED * e.energy_start
        rev = e.reversals
        if e.present and free_phase:
            holds.append(f"tension {tension}")
        parts.append(
            f"tension {tension}: peak_omega1/peak_Omega {_ratio_text(e.peak_ratio)} "
            f"({'present' if e.present else 'absent'}, threshold {e.threshold}); a run "
            f"started {_shift_text(e)} away in (X1, X1') "
            + (
                "keeps its distance (E_d "
                f"{e.energy_start:.3g} -> {e.energy_end:.3g}): a "
                "free phase, i.e. a self-excited oscillation"
                if free_phase
                else "converges to it (E_d < 1e-12 of its start): a forced response"
            )
            + f"; reversals in the steady window: {rev['slip_forward'][0]} to forward "
            f"sliding with F < 0 and {rev['slip_forward'][1]} with F >= 0, "
            f"{rev['slip_back'][0]} to backward sliding with F < 0 and "
            f"{rev['slip_back'][1]} with F >= 0"
        )
    e = evidence["allowed"]
    return holds, (
        f"base set, Vb = {e.vb:g} (Fig. 3), {e.t_end:g} s runs, steady window after "
        "30 %. " + "; ".join(parts) + ". Mechanism: friction `-mu_s sgn(Vr) F` with "
        "`F < 0` is `mu_s |F| sgn(Vr)`, along the relative velocity; every reversal "
        "from backward to forward sliding happens while Eq. (1) pulls, so the "
        "friction flips from pushing the mass backward to pushing it forward, away from "
        "the belt speed on both sides (negative damping), while the reversals back "
        "happen under a pushing contact. With the clipped law that force is 0 and "
        "derive/contraction.py proves that no self-excited vibration is possible."
    )


def _contraction(evidence):
    """The claim row "contraction (clipped)": SymPy's proof and the simulated evidence."""
    cl = contraction.claim()
    holds, numbers = [], []
    for tension in ("clipped", "allowed"):
        e = evidence[tension]
        w = e.works
        monotone = e.largest_rise <= RISE_TOLERANCE * e.energy_start
        decays = e.energy_end <= DECAYED * e.energy_start
        if decays and monotone and (tension == "allowed" or cl.proved_by_sympy):
            holds.append(f"tension {tension}")
        numbers.append(
            f"tension {tension}: E_d {e.energy_start:.3g} -> "
            + (f"< {DECAYED:.0e} of that" if decays else f"{e.energy_end:.3g}")
            + (
                ", never rising"
                if monotone
                else f" (largest rise between samples {e.largest_rise:.2g})"
            )
            + f"; friction work on the difference {w['work_friction_push']:+.3g} while "
            "F >= 0 and "
            + (
                f"{w['work_friction_pull']:+.3g} while F < 0"
                if w["work_friction_pull"]
                else "none while F < 0 (F never is)"
            )
            + f", dashpot {w['work_viscous']:+.3g}"
        )
    sympy_steps = "; ".join(
        f"{s.name} ({'proved' if s.proved else 'NOT proved'})" for s in cl.steps if s.how == "SymPy"
    )
    words = "; ".join(s.detail for s in cl.steps if s.how == "words")
    breaks = "; ".join(f"{k}: {d}" for k, (ok, d) in cl.breaks.items() if ok)
    e = evidence["clipped"]
    return holds, (
        f"SymPy (derive/contraction.py): {sympy_steps}. So `dE_d/dt = -c1 e'^2 - mu_s F "
        "(s_a - s_b)(Vr_a - Vr_b) <= -c1 e'^2` while `F >= 0` (always, clipped); "
        f"converse: {cl.converse}. In words: {words}. Conditions: "
        + "; ".join(cl.conditions)
        + f". Without them (SymPy): {breaks}. Numerically "
        f"(base set, Vb = {e.vb:g}, {e.t_end:g} s, second run offset {_shift_text(e)} in "
        "(X1, X1')): " + "; ".join(numbers) + "."
    )


def _simulated(check, evidence):
    """``check`` on the simulated evidence, or "not checked" without it."""

    def run():
        return ([], _NOT_CHECKED) if evidence is None else check(evidence())

    return run


def claims(evidence: Callable[[], dict] | None = None) -> tuple[Claim, ...]:
    """The paper's claims in words, each with its check.

    ``evidence`` returns the simulated numbers per tension law (module docstring);
    without it the two simulated claims are not checked.
    """
    return (
        Claim(
            "omega1 peak (Fig. 2b)",
            "Sect. 3, Fig. 2b",
            "the omega1 peak of Fig. 2b is friction-induced vibration of the model",
            ("tension allowed", "tension clipped"),
            _simulated(_omega1_peak, evidence),
            lambda: f"{_PAPER_LAW}, simulated",
        ),
        Claim(
            "mu_s absent",
            "Sect. 4.1 below Eq. 12",
            "`mu_s` appears in `J^0` but not in the characteristic equation",
            (),
            _claim_mu_s,
            _laws_mu_s,
        ),
        Claim(
            "only mu_bar'",
            "Sect. 4.3 (Fig. 9 text)",
            "only `mu_bar'`, not `mu_bar^0`, remains in `a1..a4`",
            (),
            _claim_only_slope,
            _laws_only_slope,
        ),
        Claim(
            "fit error",
            "below Eq. 17",
            "the cubic fit has a maximum error of about 1e-2",
            ("relative to X2max^(3/2)", "absolute, base set"),
            _claim_fit,
        ),
        Claim(
            "overdamped normal",
            "Sect. 4.2 end",
            "with `beta2* = 0.15` the normal direction is overdamped (unforced and forced)",
            (),
            _claim_overdamped,
        ),
        Claim(
            "bifurcation ~ 8",
            "Sect. 4.2, Fig. 5; Sect. 4.3, Fig. 7",
            "base set: positive growth rate for `Vb` below about 8 m/s, stable above",
            tuple(f"V_hat {m}, convention {c}" for m in friction.VHAT_MODELS for c in CONVENTIONS),
            _claim_bifurcation,
        ),
        Claim(
            "slope (Fig. 9)",
            "Sect. 4.3, Fig. 9",
            "`mu_bar'` rises with `Vb`, goes to infinity as `Vb -> Vhat`, is zero above "
            "`Vhat`, and spans from nearly zero to infinity",
            (),
            _claim_slope,
        ),
        Claim(
            "unforced limit",
            "Sects. 4.2-4.3",
            "when `mu_bar' = 0` the forced characteristic equation is the unforced one",
            (),
            _claim_unforced_limit,
        ),
        Claim(
            "A3-A6 = Eqs. 18-21",
            "Appendix A.2",
            "Eqs. A3-A6 are the slow equations (18)-(21) in state-space form",
            (),
            _claim_state_space,
        ),
        Claim(
            "contraction (clipped)",
            "beyond the paper (docs/modelling.md#tension)",
            "two tangential motions under one normal motion converge when the contact "
            "cannot pull: no self-excited vibration, no coexistence",
            ("tension clipped", "tension allowed"),
            _simulated(_contraction, evidence),
            _laws_contraction,
        ),
    )


def check_claim(claim: Claim) -> ClaimResult:
    holds, evidence = claim.check()
    unknown = [h for h in holds if h and h not in claim.readings]
    if unknown:
        raise ValueError(f"{claim.key}: readings {unknown} not declared")
    if holds == [""]:
        status = "holds"
    elif holds and len(holds) == len(claim.readings):
        status = "holds"
    elif holds:
        status = "holds under reading " + "; ".join(f"`{h}`" for h in holds)
    else:
        status = "does not hold"
    return ClaimResult(claim, status, evidence, claim.laws())
