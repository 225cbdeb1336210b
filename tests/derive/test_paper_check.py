"""The paper check (beltmdsm.derive.paper, beltmdsm.derive.paper_check): engine,
transcriptions, findings."""

import re

import numpy as np
import pytest
import sympy as sp
from sympy.parsing.sympy_parser import TokenError

from beltmdsm.derive import codegen, paper, paper_check, stability
from beltmdsm.derive.model import FRICTION_LAWS, P
from beltmdsm.derive.statespace import jacobian_at_equilibrium_eq_11
from beltmdsm.model import Model
from beltmdsm.paper_reports import contraction_evidence as evidence

#: Every numbered equation the report must cover (issue 4).
REQUIRED = (
    [f"Eq. {n}" for n in (*range(4, 13), *range(13, 25), 26, 27, 28)]
    + ["Eq. 25 (mu_bar^0)", "Eq. 25 (mu_bar')"]
    + [f"Eq. A{n}" for n in range(1, 9)]
)
PARSE_ERRORS = (SyntaxError, NameError, TypeError, TokenError)


@pytest.fixture(scope="module")
def checked():
    """One full run of the check (rows and claims), shared by the tests below."""
    results, claims = paper_check.run(evidence=evidence.paper_evidence)
    return (
        {r.row.key: r for r in results},
        {c.claim.key: c for c in claims},
        paper_check.report(results, claims),
    )


def _row(key, printed, derived_of_convention=None, derived=None):
    if derived_of_convention is not None:
        variants = tuple(
            paper_check.Variant(printed, derived_of_convention(c), c) for c in stability.CONVENTIONS
        )
    else:
        variants = (paper_check.Variant(printed, derived),)
    return paper_check.Row(key, "test", variants)


# The engine with deliberately wrong transcriptions --------------------------------------


def test_flipped_sign_is_reported_as_differs():
    wrong = paper.EQ_11.replace("-omega1**2", "omega1**2")
    assert wrong != paper.EQ_11
    result = paper_check.check_row(
        _row("Eq. 11", lambda: paper.parse(wrong), derived=jacobian_at_equilibrium_eq_11)
    )
    assert result.status == "differs"
    assert "entry (2,1)" in result.explanation and "2*omega1**2" in result.explanation
    assert result.problems  # a difference without a reason is flagged


def test_wrong_exponent_is_reported_as_differs():
    wrong = paper.EQ_9.replace("**(2/3)", "**(1/3)")
    assert wrong != paper.EQ_9
    result = paper_check.check_row(
        _row(
            "Eq. 9",
            lambda: paper.parse(wrong),
            derived=lambda: sp.Matrix([paper.eq_9()[i] for i in range(4)]),
        )
    )
    assert result.status == "differs" and "component 3" in result.explanation


def test_numeric_path_reports_a_wrong_piecewise_transcription():
    """Eq. 23 with arccos replaced by arcsin: only the numeric comparison can decide."""
    from beltmdsm.derive.friction import mu_bar_eq_23

    wrong = paper.EQ_23.replace("arccos", "arcsin")
    result = paper_check.check_row(
        _row(
            "Eq. 23",
            lambda: paper.parse(wrong, arcsin=sp.asin),
            derived=lambda: mu_bar_eq_23(stability.S1 - P["Vb"]),
        )
    )
    assert result.status == "differs"
    assert "numeric" in result.outcomes[0].method


def test_a_right_transcription_matches_and_the_method_is_named():
    result = paper_check.check_row(
        _row("Eq. 11", paper.eq_11, derived=jacobian_at_equilibrium_eq_11)
    )
    assert result.status == "matches" and result.outcomes[0].method.startswith("symbolic")
    assert result.problems == ()


def test_an_explanation_for_a_matching_variant_is_flagged_stale():
    row = paper_check.Row(
        "Eq. 11",
        "test",
        (
            paper_check.Variant(
                paper.eq_11, jacobian_at_equilibrium_eq_11, why="a reason that no longer applies"
            ),
        ),
    )
    result = paper_check.check_row(row)
    assert result.status == "matches" and "STALE" in result.explanation and result.problems


def test_shape_mismatch_breaks_the_check():
    with pytest.raises(ValueError):
        paper_check.compare(paper.eq_11(), paper.eq_9(), seed=0)


# Typos fail, they are never skipped --------------------------------------------------------


@pytest.mark.parametrize(
    "text",
    [
        "3/2*omega1**",  # syntax error
        "Matrix([[0, 1], [omega1, 0]",  # unbalanced bracket
        "omgea1**2",  # misspelt name: not silently a new symbol
        "2*beta2*omega2*X2**(3/2)*Y3",  # unknown state
    ],
)
def test_a_transcription_that_fails_to_parse_raises(text):
    with pytest.raises(PARSE_ERRORS):
        paper.parse(text)


def test_a_typo_in_a_row_fails_the_check_run():
    row = _row(
        "Eq. 11",
        lambda: paper.parse(paper.EQ_11.replace("omega1", "omgea1", 1)),
        derived=jacobian_at_equilibrium_eq_11,
    )
    with pytest.raises(NameError):
        paper_check.check_row(row)


@pytest.mark.parametrize("name", [n for n in paper.__all__ if n.startswith("eq_") and n != "eq_15"])
def test_every_transcription_parses_with_exact_numbers(name):
    expr = sp.sympify(getattr(paper, name)())
    assert expr.free_symbols and not expr.atoms(sp.Float)


def test_eq_28_transcription_agrees_with_the_one_in_stability():
    """Two transcriptions of Eq. (28) typed independently must agree."""
    mine = paper.eq_28()
    theirs = sp.Matrix(stability.hurwitz_eq_28(*paper.a_symbols))
    assert (mine - theirs).applyfunc(sp.expand) == sp.zeros(4, 1)


# The findings --------------------------------------------------------------------------------


def test_the_report_covers_every_numbered_equation(checked):
    rows, _, _ = checked
    assert set(REQUIRED) <= set(rows)
    for key, r in rows.items():
        assert r.status in ("matches", "differs") or r.status.startswith(
            "matches under convention"
        ), key


def test_every_difference_is_explained_and_no_reason_is_stale(checked):
    rows, _, _ = checked
    assert [p for r in rows.values() for p in r.problems] == []
    for r in rows.values():
        if r.status != "matches":
            assert "at the base set" in r.explanation or "seeded point" in r.explanation


def test_eq_28_differs_in_h4_only(checked):
    rows, _, _ = checked
    r = rows["Eq. 28"]
    assert r.status == "differs"
    assert "H4: printed - derived = `a1*a4**2*(a1 - 1)`" in r.explanation


@pytest.mark.parametrize("key", ["Eq. 22", "Eq. 26", "Eq. 27", "Eq. A4", "Eq. A7", "Eq. A8"])
def test_sign_dependent_equations_match_under_convention_paper_only(checked, key):
    rows, _, _ = checked
    assert rows[key].status == "matches under convention `paper`"


@pytest.mark.parametrize(
    "key",
    [
        "Eq. 4",
        "Eq. 9",
        "Eq. 10",
        "Eq. 11",
        "Eq. 12",
        "Eq. 17",
        "Eq. 18",
        "Eq. 19",
        "Eq. 20",
        "Eq. 21",
        "Eq. 23",
        "Eq. 25 (mu_bar')",
        "Eq. A1",
        "Eq. A2",
    ],
)
def test_equations_that_match(checked, key):
    rows, _, _ = checked
    assert rows[key].status == "matches"


def test_claims(checked):
    _, claims, _ = checked
    assert claims["mu_s absent"].status == "holds"
    assert claims["only mu_bar'"].status == "holds"
    assert claims["overdamped normal"].status == "holds"
    assert claims["slope (Fig. 9)"].status == "holds"
    assert claims["fit error"].status == "holds under reading `relative to X2max^(3/2)`"
    assert "`8*X2max**(3/2)/1155` at `X2 = 0`" in claims["fit error"].evidence
    bif = claims["bifurcation ~ 8"]
    assert bif.status == "holds under reading `V_hat tangential, convention paper`"
    assert "unstable [0, 8.521)" in bif.evidence and "[0, 6.375)" in bif.evidence
    assert claims["A3-A6 = Eqs. 18-21"].status == "does not hold"


def test_the_report_in_the_tree_is_up_to_date(checked):
    _, _, text = checked
    path = codegen.GENERATED / paper_check.REPORT
    assert path.read_text() == text, "run `python -m derive check-paper`"
    assert text.count("\n| Eq. ") == len(checked[0])


# The simulated claims (derive/contraction.py) ---------------------------------------------


def _allowed_runs():
    """The pair of runs behind the claims' evidence under the allowed law."""
    return evidence.difference_runs(
        evidence.SHIFT, Model(Vb=evidence.VB, tension="allowed"), t_end=evidence.T_END
    )


def test_without_the_simulation_the_simulated_claims_are_not_checked():
    claims = {c.key: c for c in paper_check.claims()}
    for key in ("omega1 peak (Fig. 2b)", "contraction (clipped)"):
        holds, text = claims[key].check()
        assert holds == [] and text.startswith("not checked: the simulation of Eq. (4)")


def _counts(evidence, tension):
    part = evidence.split(f"tension {tension}:")[1]
    m = re.search(
        r"(\d+) to forward sliding with F < 0 and (\d+) with F >= 0, (\d+) to "
        r"backward sliding with F < 0 and (\d+) with F >= 0",
        part,
    )
    return tuple(int(x) for x in m.groups())


def test_the_omega1_peak_is_self_excited_only_with_tension(checked):
    _, claims, _ = checked
    peak = claims["omega1 peak (Fig. 2b)"]
    assert peak.status == "holds under reading `tension allowed`"
    assert "peak_omega1/peak_Omega = 0.70 (present" in peak.evidence
    assert "peak_omega1/peak_Omega < 1e-4 (absent" in peak.evidence
    fwd_pull, fwd_push, back_pull, back_push = _counts(peak.evidence, "allowed")
    assert fwd_pull > 100 and fwd_push == 0 and back_pull == 0 and back_push > 100
    assert _counts(peak.evidence, "clipped") == (0, 0, 0, 0)


def test_the_reversal_counts_against_the_samples(checked):
    """Independent count: upward zero crossings of Vr = X1' - Vb on the 0.02 s samples."""
    _, claims, _ = checked
    run = _allowed_runs()
    sim = run.a
    w = sim.t >= sim.settings.window_start
    vr, F = sim.y[1, w] - sim.params["Vb"], sim.normal_force[w]
    up = np.flatnonzero((vr[:-1] < 0) & (vr[1:] >= 0))
    down = np.flatnonzero((vr[:-1] > 0) & (vr[1:] <= 0))
    fwd_pull, fwd_push, back_pull, back_push = _counts(
        claims["omega1 peak (Fig. 2b)"].evidence, "allowed"
    )
    assert up.size == fwd_pull + fwd_push and down.size == back_pull + back_push
    # the force at the sample next to each crossing (F moves little in 0.02 s)
    assert np.all(np.minimum(F[up], F[up + 1]) < 0)
    assert np.all(np.maximum(F[down], F[down + 1]) >= 0)


def test_the_contraction_claim(checked):
    _, claims, _ = checked
    c = claims["contraction (clipped)"]
    assert c.status == "holds under reading `tension clipped`"
    assert "NOT proved" not in c.evidence and c.evidence.count("(proved)") == 8
    clipped = c.evidence.split("tension clipped:")[1].split("tension allowed:")[0]
    assert "never rising" in clipped and "none while F < 0" in clipped
    allowed = c.evidence.split("tension allowed:")[1]
    assert "largest rise between samples" in allowed
    works = evidence.paper_evidence()["allowed"].works
    assert works["work_friction_pull"] > 0 >= works["work_friction_push"]


@pytest.mark.parametrize(
    "key,laws",
    [
        ("Eq. 6", ("coulomb",)),
        ("Eq. 9", ("coulomb",)),
        ("Eq. 12", ("coulomb", "static_kinetic")),  # no friction coefficient in it
        ("Eq. 23", ("coulomb",)),
        ("Eq. 25 (mu_bar')", ("coulomb",)),
        ("Eq. 7", "every law"),
        ("Eq. 17", "every law"),
        ("Eq. 22", "every law"),
        ("Eq. A8", "every law"),
    ],
)
def test_rows_that_hold_for_coulomb_only_say_so(checked, key, laws):
    """A row whose derivation takes the friction law is derived for Stribeck's too: where
    that differs the row holds for Coulomb's law only, with a numeric example; the MDSM
    rows are written in mu_bar, whatever law it averages, and hold for every law."""
    rows, _, text = checked
    if laws == "every law":  # the registry's, so that adding a law breaks no test
        laws = tuple(FRICTION_LAWS)
    assert rows[key].laws == laws
    if laws == ("coulomb",):
        assert "stribeck: " in rows[key].law_detail
        assert f"| {key} |" in text and "coulomb only (stribeck" in text


def test_claims_say_for_which_friction_laws_they_hold(checked):
    _, claims, _ = checked
    # static_kinetic slips at a constant mu_k: its determinant is Coulomb's too. A law a
    # user adds is listed on its side (the registry's laws, not a fixed list)
    free, rest = claims["mu_s absent"].laws.split(" only (")
    assert free.split(", ")[:2] == ["coulomb", "static_kinetic"] and "stribeck" not in free
    assert "stribeck: mu_s enters through the slope mu'(Vb)" in rest
    assert all(law in free or f"{law}: " in rest for law in FRICTION_LAWS)
    assert claims["only mu_bar'"].laws.startswith("every law")
    contraction = claims["contraction (clipped)"].laws
    assert "coulomb: proved" in contraction and "stribeck: NOT proved" in contraction
    assert "0 < |Vr| < oo" in contraction and "mu_k < mu_s" in contraction
