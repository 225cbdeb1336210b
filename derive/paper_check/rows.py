"""The rows of the paper check: every numbered equation with its derivation, in paper order.

Each row pairs a transcription of `beltmdsm.derive.paper` (typed by hand exactly as printed)
with the expression the package derives; `beltmdsm.derive.paper_check.engine` compares them.
Rows whose derivation takes the friction law (``by_law=True``) are also derived for
every other law of the registry: Eqs. 4, 6, 9-12 and 23-25 hold for Coulomb's law
only (the MDSM rows are written in the effective friction ``mu_bar``, whatever law it
averages).
"""

from __future__ import annotations

import sympy as sp

from .. import friction, mdsm, paper, stability, statespace
from ..fit import coefficients_eq_17, polynomial_eq_16
from ..model import STATE, X2, P, equations_of_motion
from .engine import CONVENTIONS, Row, Variant, d

__all__ = ["rows", "FAST"]


def _matrix(values):
    return sp.Matrix(list(values))


def _eq4_printed():
    sol = sp.solve(list(paper.eq_4()), [paper.X1ddot, paper.X2ddot], dict=True)
    if len(sol) != 1:
        raise RuntimeError(f"Eq. (4) does not determine the accelerations: {sol}")
    return sp.Matrix([sol[0][paper.X1ddot], sol[0][paper.X2ddot]])


def _state(i):
    return lambda law: statespace.state_space_eqs_5_8(friction=law)[i]


def _slow(i, convention):
    return lambda: stability.slow_state_space_A3_A6(convention)[i]


def _forced_charpoly(convention):
    return lambda: statespace.charpoly_eq_12(stability.forced_jacobian_eq_22(convention)).as_expr()


_A1, _A2, _PH1, _PH2 = sp.symbols("A1 A2", positive=True) + sp.symbols("phi1 phi2", real=True)
#: Fast monomials whose average the MDSM uses (Eq. 15 must agree with them).
FAST = (
    mdsm.Phi1,
    mdsm.Phi2,
    sp.diff(mdsm.Phi1, mdsm.theta),
    mdsm.Phi2**2,
    mdsm.Phi2**3,
    mdsm.Phi1 * mdsm.Phi2,
    mdsm.Phi2**2 * sp.diff(mdsm.Phi2, mdsm.theta),
    mdsm.Phi2 * sp.diff(mdsm.Phi2, mdsm.theta) ** 2,
)


def _harmonic(f):
    shapes = {
        mdsm.Phi1: _A1 * sp.sin(mdsm.theta + _PH1),
        mdsm.Phi2: _A2 * sp.sin(mdsm.theta + _PH2),
    }
    return f.subs(shapes).doit()


def _eq15_printed():
    return sp.Matrix([sp.simplify(paper.eq_15(_harmonic(f))) for f in FAST])


def _eq15_derived():
    return sp.Matrix(
        [sp.simplify(mdsm.harmonic_averages(mdsm.avg(f), _A1, _A2, _PH1, _PH2)) for f in FAST]
    )


_WHY_CONSISTENT = (
    "with the sign of Eq. (4), `-mu_bar(Z1'-Vb) F_n` (as Eq. 20 prints it), "
    "every friction term changes sign;"
)
_WHY_PAPER_SIGN = (
    "Eq. (A4) carries `+mu_bar F_n` with `mu_bar` of Eq. (23) negative for "
    "`V_r < 0`, i.e. friction pushing against the belt; Eq. (20) and the MDSM "
    "derivation give `-mu_bar F_n`;"
)


def rows() -> tuple[Row, ...]:
    """Every numbered equation of the paper with its derivation."""

    def conv(printed, derived_of, whys, names=()):
        return tuple(
            Variant(printed, derived_of(c), c, whys.get(c, ""), names) for c in CONVENTIONS
        )

    def J11(law):
        return statespace.jacobian_at_equilibrium_eq_11(friction=law)

    def eq9(law):
        return _matrix(statespace.equilibrium_eq_9(friction=law)[s] for s in STATE)

    return (
        Row(
            "Eq. 4",
            "equations of motion, solved for the accelerations",
            (
                Variant(
                    _eq4_printed,
                    lambda law: equations_of_motion(general=False, friction=law),
                    by_law=True,
                ),
            ),
        ),
        Row("Eq. 5", "state equation `X1' = Y1`", (Variant(paper.eq_5, _state(0), by_law=True),)),
        Row(
            "Eq. 6",
            "state equation `Y1'` (branch `X1' < Vb`)",
            (Variant(paper.eq_6, _state(1), by_law=True),),
        ),
        Row("Eq. 7", "state equation `X2' = Y2`", (Variant(paper.eq_7, _state(2), by_law=True),)),
        Row("Eq. 8", "state equation `Y2'`", (Variant(paper.eq_8, _state(3), by_law=True),)),
        Row("Eq. 9", "unforced equilibrium", (Variant(paper.eq_9, eq9, by_law=True),)),
        Row(
            "Eq. 10",
            "Jacobian of Eqs. 5-8",
            (
                Variant(
                    paper.eq_10,
                    lambda law: statespace.jacobian_eq_10(friction=law),
                    by_law=True,
                ),
            ),
        ),
        Row("Eq. 11", "Jacobian at equilibrium `J^0`", (Variant(paper.eq_11, J11, by_law=True),)),
        Row(
            "Eq. 12",
            "characteristic polynomial of the printed `J^0`",
            (
                Variant(
                    paper.eq_12,
                    lambda law: statespace.charpoly_eq_12(J11(law)).as_expr(),
                    by_law=True,
                ),
            ),
        ),
        Row(
            "Eq. 13",
            "MDSM split of `X1`",
            (Variant(paper.eq_13, lambda: mdsm.split_eqs_13_14()[0][0]),),
        ),
        Row(
            "Eq. 14",
            "MDSM split of `X2`",
            (Variant(paper.eq_14, lambda: mdsm.split_eqs_13_14()[0][1]),),
        ),
        Row(
            "Eq. 15",
            "fast average (printed integral) against the MDSM averages, "
            "harmonic `Phi`, for "
            + ", ".join(f"`{sp.sstr(f)}`" for f in FAST[:2])
            + " and six products",
            (Variant(_eq15_printed, _eq15_derived),),
        ),
        Row(
            "Eq. 16",
            "cubic in `X2` with the printed coefficients",
            (Variant(paper.eq_16, lambda: polynomial_eq_16(X2, 3)),),
        ),
        Row(
            "Eq. 17",
            "least-squares coefficients `c3, c2, c1, c0`",
            (
                Variant(
                    paper.eq_17,
                    lambda: _matrix(reversed(coefficients_eq_17(3))),
                    names=("c3", "c2", "c1", "c0"),
                ),
            ),
        ),
        Row(
            "Eq. 18",
            "slow tangential equation with the cubic",
            (Variant(paper.eq_18, lambda: mdsm.slow_equations_18_19()[0]),),
        ),
        Row(
            "Eq. 19",
            "slow normal equation with the cubic",
            (Variant(paper.eq_19, lambda: mdsm.slow_equations_18_19()[1]),),
        ),
        Row(
            "Eq. 20",
            "slow tangential equation with `Z2^(3/2)`",
            (Variant(paper.eq_20, lambda: mdsm.slow_equations_20_21()[0]),),
        ),
        Row(
            "Eq. 21",
            "slow normal equation with `Z2^(3/2)`",
            (Variant(paper.eq_21, lambda: mdsm.slow_equations_20_21()[1]),),
        ),
        Row(
            "Eq. 22",
            "forced Jacobian `J_f^0`",
            conv(
                paper.eq_22,
                lambda c: lambda: stability.forced_jacobian_eq_22(c),
                {"consistent": _WHY_CONSISTENT},
            ),
        ),
        Row(
            "Eq. 23",
            "effective friction (arc-cosine form)",
            (
                Variant(
                    paper.eq_23,
                    lambda law: friction.mu_bar_eq_23(stability.S1 - P["Vb"], law),
                    by_law=True,
                ),
            ),
        ),
        Row(
            "Eq. 24",
            "first-order expansion of the printed Eq. 23 at `Z1' = 0`",
            (
                Variant(
                    paper.eq_24,
                    lambda law: stability.with_friction(
                        stability.mu0 + stability.mu1 * stability.S1, law
                    ),
                    by_law=True,
                ),
            ),
        ),
        Row(
            "Eq. 25 (mu_bar^0)",
            "`mu_bar^0 = mu_bar(Z1'^0)` with Eq. 23",
            (
                Variant(
                    lambda: paper.eq_25_mu0("Z1dot"),
                    friction.mu_bar0_eq_25,
                    "argument Z1'",
                    by_law=True,
                ),
                Variant(
                    lambda: paper.eq_25_mu0("Vr"),
                    friction.mu_bar0_eq_25,
                    "argument V_r",
                    "read as Eq. (23)'s `mu_bar(V_r)` at `V_r = Z1'^0 = 0` the value is "
                    "`mu_bar(0) = 0`; the expansion point of Eq. (24) is `Z1' = 0`, "
                    "i.e. `V_r = -Vb`;",
                    by_law=True,
                ),
            ),
        ),
        Row(
            "Eq. 25 (mu_bar')",
            "slope of the effective friction, for `Vhat > Vb`",
            (
                Variant(
                    paper.eq_25_slope,
                    friction.mu_bar_slope_eq_25,
                    assume={P["Vhat"]: P["Vb"] + d},
                    by_law=True,
                ),
            ),
        ),
        Row(
            "Eq. 26",
            "characteristic polynomial of the printed `J_f^0`",
            conv(
                paper.eq_26,
                _forced_charpoly,
                {
                    "consistent": "inherits Eq. (22): the `mu_bar' g` term changes sign "
                    "(`mu_bar^0` drops out of the determinant);"
                },
            ),
        ),
        Row(
            "Eq. 27",
            "quartic with the printed `a1..a4` of Eq. A8",
            conv(
                paper.eq_27,
                _forced_charpoly,
                {"consistent": "inherits Eq. (22): every `mu_bar'` term changes sign;"},
            ),
        ),
        Row(
            "Eq. 28",
            "Hurwitz determinants `H1..H4` (generic `a1..a4`)",
            (
                Variant(
                    paper.eq_28,
                    lambda: _matrix(stability.hurwitz_determinants(*paper.a_symbols)),
                    why="the printed `H4` has `a1 a4^2` where the 4th leading minor of the "
                    "Hurwitz matrix (= `a4 H3`) has `a1^2 a4^2`; the printed term is "
                    "dimensionally inconsistent (`a_k` ~ 1/s^k: s^-9 among s^-10);",
                    names=("H1", "H2", "H3", "H4"),
                ),
            ),
        ),
        Row(
            "Eq. A1",
            "fast tangential equation (residual)",
            (Variant(paper.eq_A1, lambda: mdsm.fast_equations_A1_A2()[0]),),
        ),
        Row(
            "Eq. A2",
            "fast normal equation (residual)",
            (Variant(paper.eq_A2, lambda: mdsm.fast_equations_A1_A2()[1]),),
        ),
        Row(
            "Eq. A3", "slow state equation `Z1' = S1`", conv(paper.eq_A3, lambda c: _slow(0, c), {})
        ),
        Row(
            "Eq. A4",
            "slow state equation `S1'`",
            conv(paper.eq_A4, lambda c: _slow(1, c), {"consistent": _WHY_PAPER_SIGN}),
        ),
        Row(
            "Eq. A5", "slow state equation `Z2' = S2`", conv(paper.eq_A5, lambda c: _slow(2, c), {})
        ),
        Row("Eq. A6", "slow state equation `S2'`", conv(paper.eq_A6, lambda c: _slow(3, c), {})),
        Row(
            "Eq. A7",
            "slow equilibrium",
            conv(
                paper.eq_A7,
                lambda c: (
                    lambda: _matrix(stability.slow_equilibrium_A7(c)[s] for s in stability.SLOW)
                ),
                {
                    "consistent": "with the sign of Eq. (4), `Z1^0 = -mu_bar^0 g/omega1^2 > 0` "
                    "(like `X1^0` of Eq. 9); the printed `Z1^0` is negative;"
                },
            ),
        ),
        Row(
            "Eq. A8",
            "coefficients `a1..a4` of the quartic",
            conv(
                paper.eq_A8,
                lambda c: lambda: _matrix(stability.coefficients_A8(c)),
                {"consistent": "inherits Eq. (22): every `mu_bar'` term changes sign;"},
                names=("a1", "a2", "a3", "a4"),
            ),
        ),
    )
