"""What `register` decides about a law before any derivation (issue 41, items 3, 4, 6).

* ``mu(0)`` is the limit of ``mu(s)`` as ``s -> 0+``: a removable singularity at rest
  (``tanh(s/v_s)/(s/v_s)``) has its value 1 there, where substituting ``s = 0`` gives NaN;
  a law whose value at rest is not finite (Dieterich-Ruina's steady state
  ``mu_0 + (a - b) ln(s/V0)``) is refused at `register`, by name, in one line;
* ``static=`` is checked at `register` as ``coefficient`` is: an undeclared parameter or
  a foreign symbol is refused in one line, not a minute into the derivation;
* wording: a law with an internal state (LuGre's ``z``) is "not supported yet", the
  cubic law's ``friction_monotone`` reason names its positive root only, and no
  capability reason carries SymPy's own text.
"""

import pytest
import sympy as sp

from beltmdsm.derive import averaging, contraction_sign, lawcheck, laws, model
from beltmdsm.derive.lawcheck import UnsupportedLaw, value_at_rest
from beltmdsm.derive.parameters import Parameter

V_S = dict(v_s=Parameter("v_s", "m/s", 1.0, "positive", "a speed"))


def _law(name, coefficient, parameters=(), static=None):
    return laws.FrictionLaw(
        name, "a test law", "doc", "none", parameters, coefficient=coefficient, static=static
    )


@pytest.fixture
def registered(monkeypatch):
    """Enter a law in the registry for one test (the registry is restored after it)."""

    def add(law):
        monkeypatch.setitem(laws.LAWS["friction"], law.name, law)
        return law.name

    return add


def _refused(law):
    before = dict(laws.LAWS["friction"])
    with pytest.raises(UnsupportedLaw) as refused:
        laws.register("friction", law)
    assert laws.LAWS["friction"] == before
    message = str(refused.value)
    assert "\n" not in message and message.startswith(f"friction law {law.name!r}: ")
    return message


def test_the_value_at_rest_of_a_removable_singularity_is_its_limit(registered):
    s = sp.Symbol("s", positive=True)
    v = sp.Symbol("v", positive=True)
    assert sp.nan == (sp.tanh(s / v) / (s / v)).subs(s, 0)  # what a substitution gives
    assert value_at_rest(sp.tanh(s / v) / (s / v), s) == 1
    assert value_at_rest(sp.sin(s) / s + v, s) == 1 + v
    name = registered(_law("tanh_ratio", lambda P, s: sp.tanh(s / P["v_s"]) / (s / P["v_s"])))
    assert model.rest_coefficient(name) == 1
    assert model.static_coefficient(name) == 1  # the stick cone's bound, from the limit


@pytest.mark.parametrize(
    "coefficient, shown",
    [
        (lambda P, s: P["mu_s"] + (P["v_s"] - P["mu_s"]) * sp.log(s / P["v_s"]), "oo*sign("),
        (lambda P, s: P["mu_s"] + P["v_s"] / s, "oo"),
    ],
    ids=["dieterich-ruina", "pole"],
)
def test_a_law_whose_value_at_rest_is_not_finite_is_refused_by_name(coefficient, shown):
    message = _refused(_law("rate_state", coefficient))
    assert "its value at rest, the limit of mu(s) as s -> 0+, is " + shown in message
    assert "not finite" in message


def test_a_finite_law_with_a_real_parameter_is_accepted():
    """mu_s + c_r s with c_r of the real domain: mu(0) = mu_s is finite, the law passes."""
    c_r = (Parameter("c_r", "s/m", 0.01, "real", "a slope of either sign"),)
    law = _law("real_slope_probe", lambda P, s: P["mu_s"] + P["c_r"] * s, c_r)
    assert lawcheck.check("friction", law, laws.parameter_table() + c_r) is None


@pytest.mark.parametrize(
    "static, construct",
    [
        (lambda P: P["mu_top"], "its static bound: P['mu_top'] is neither a parameter"),
        (lambda P: P["mu_s"] + sp.Symbol("t"), "its static bound: symbol t is neither"),
        (lambda P: sp.Function("z")(sp.Symbol("t")), "its static bound: undefined function z(t)"),
        (lambda P: [P["mu_s"]], "its static bound: [mu_s] is not an expression"),
        (lambda P: sp.oo + P["mu_s"], "its static bound oo is not finite"),
    ],
    ids=["undeclared", "foreign-symbol", "state", "not-an-expression", "infinite"],
)
def test_static_is_checked_at_register(static, construct):
    message = _refused(_law("static_probe", lambda P, s: P["mu_k"], static=static))
    assert construct in message


def test_a_law_with_internal_state_is_not_supported_yet():
    """LuGre's bristle deflection z, written as a name of P or as a symbol: the refusal
    says that laws with internal state are not supported yet (declaring z as a Parameter
    would make the law silently memoryless)."""
    for coefficient in (
        lambda P, s: P["mu_s"] + P["sigma0"] * P["z"],
        lambda P, s: P["mu_s"] + sp.Symbol("z") * s,
    ):
        message = _refused(_law("lugre", coefficient))
        assert "laws with internal state (LuGre's bristle deflection) are not supported yet" in (
            message
        )


def test_the_cubic_laws_monotonicity_names_its_positive_root_only(registered):
    """mu_s - c_1 s + c_3 s^3 (written with parameters of the table, mu_k and v_s, as a
    test may: the model's symbols are made at import): dmu/ds = 0 at s = +-sqrt(c_1 /
    (3 c_3)), of which only the positive root is a sliding speed."""
    name = registered(_law("cubic_probe", lambda P, s: P["mu_s"] - P["mu_k"] * s + P["v_s"] * s**3))
    m = contraction_sign.monotonicity(name)
    assert not m.holds
    listed = m.reason[m.reason.index("(roots at [") + 11 : m.reason.index("])")]
    roots = [sp.sympify(r, locals=model.P) for r in listed.split(", ")]
    assert roots == [sp.sqrt(model.P["mu_k"] / (3 * model.P["v_s"]))], m.reason


def test_no_sympy_text_leaks_into_the_risch_reason(registered, monkeypatch):
    """A law where SymPy's Risch implementation gives up (NotImplementedError, whose text
    tells the user of SymPy to try a flag): the reason is the package's own words."""

    def gives_up(*args, **kwargs):
        raise NotImplementedError(
            "Try using a manual extension with the extension flag (SymPy's own words)"
        )

    monkeypatch.setattr(averaging, "risch_integrate", gives_up)
    name = registered(_law("risch_probe", lambda P, s: P["mu_s"] / (1 + s**2)))
    holds, why = averaging._risch(name)
    assert not holds and "extension flag" not in why and "SymPy" in why
    assert why.startswith("risch_probe: ") and "quadrature" in why
