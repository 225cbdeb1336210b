"""What made the derivation faster decides as the slow path did (issue 41, item 7).

The time itself is measured by benchmarks/bench_derive.py (CPU time and peak memory per
added law, against the derivation before item 7, in the same run); these tests check
the shortcuts, not the clock:

* a ``p(Vb) = 0`` whose polynomial (cleared of radicals) has an irreducible factor of
  degree > 2 claims no closed form and is not solved (the rational-root law's ran to
  its 20 s budget on every first derivation); a quadratic one is still solved (the
  cubic law's root, against its closed form typed here);
* the printers' cached term order prints what SymPy's own printers print, and so does
  each printing kept per printer (its hoisted roots and Floats of other precisions
  included);
* the fit's factored forms are ``sympy.factor``'s, and its largest error is the one a
  comparison at 50 digits picks (ties included);
* the kept ``simplify`` and ``factor`` results are SymPy's.

Byte-identity of generated/ with the slower path is ``python -m derive --check``
(tests/derive/test_codegen.py).
"""

import json
import math
import subprocess
import sys

import sympy as sp
from sympy.printing.numpy import NumPyPrinter
from sympy.printing.pycode import MpmathPrinter, PythonCodePrinter

from beltmdsm.derive import fit, memo
from beltmdsm.derive.codegen.printers import Mpmath, NumPy, Scalar
from beltmdsm.derive.statespace import _largest_irreducible_degree

x, a, b = sp.symbols("x a b", positive=True)


def test_the_degree_test_clears_denominators_and_radicals():
    assert _largest_irreducible_degree(x**2 - a, x) == 2
    assert _largest_irreducible_degree(sp.sqrt(1 + x**2) - a * x, x) == 2
    # the rational-root law's slope: x (1 + x^2)^(-3/2) = a is a cubic in x^2
    assert _largest_irreducible_degree(x / (1 + x**2) ** sp.Rational(3, 2) - a, x) == 6
    # factors of low degree are found: (x - a)(x^2 + b) has none above 2
    assert _largest_irreducible_degree(sp.expand((x - a) * (x**2 + b)), x) == 2
    assert _largest_irreducible_degree(x**3 - a, x) == 3
    # not algebraic in x: left to solve
    assert _largest_irreducible_degree(sp.exp(x / a) - b, x) == 0


_PROGRAM = """
import json
import sympy as sp
from beltmdsm.derive import laws
from beltmdsm.derive.parameters import Parameter

laws.register("friction", laws.FrictionLaw(
    "rational_sqrt", "mu_k + (mu_s - mu_k) / sqrt(1 + (|Vr|/v_s)^2)", "d", "e",
    laws.LAWS["friction"]["stribeck"].parameters,
    coefficient=lambda P, s: P["mu_k"] + (P["mu_s"] - P["mu_k"]) / sp.sqrt(1 + (s / P["v_s"])**2)))
laws.register("friction", laws.FrictionLaw(
    "cubic", "mu_s - mu_1 |Vr| + mu_3 |Vr|^3", "d", "e",
    (Parameter("mu_1", "s/m", 0.3, "nonnegative", "linear fall of mu"),
     Parameter("mu_3", "s^3/m^3", 0.1, "positive", "cubic rise of mu")),
    coefficient=lambda P, s: P["mu_s"] - P["mu_1"] * s + P["mu_3"] * s**3))
from beltmdsm.derive import budget, statespace  # after the laws: the parameters include theirs

budget.use_record(None)
P = statespace.P
rational = statespace.critical_belt_speed("hertz_damp", "rational_sqrt")
cubic = statespace.critical_belt_speed("hertz_damp", "cubic")
at = {P["beta1"]: 0.05, P["omega1"]: 2.0, P["g"]: 9.81, P["mu_1"]: 0.3, P["mu_3"]: 0.1}
print(json.dumps({
    "rational": str(rational),
    "degree": statespace._largest_irreducible_degree(
        statespace.tangential_damping("hertz_damp", "rational_sqrt"), P["Vb"]),
    "cubic": float(cubic.subs(at)),
    "steps": sorted(what for what, _ in budget._DECIDED),
}))
"""


def test_a_p_of_vb_of_degree_above_two_is_not_solved_and_a_quadratic_one_is():
    out = subprocess.run(
        [sys.executable, "-c", _PROGRAM], capture_output=True, text=True, timeout=600
    )
    assert out.returncode == 0, out.stderr[-3000:]
    got = json.loads(out.stdout)
    assert got["degree"] == 6
    assert got["rational"] == "None"  # no closed form claimed
    assert "rational_sqrt: p(Vb) = 0" not in got["steps"]  # and sympy.solve not run
    assert "cubic: p(Vb) = 0" in got["steps"]
    # p = 2 beta1 omega1 + g (-mu_1 + 3 mu_3 Vb^2) = 0, typed by hand
    expected = math.sqrt((0.3 * 9.81 - 2 * 0.05 * 2.0) / (3 * 0.1 * 9.81))
    assert math.isclose(got["cubic"], expected, rel_tol=1e-14)


def test_the_cached_term_order_prints_what_sympys_printers_print():
    exprs = [
        a + b + x,
        sp.sqrt(x**2 + a) - 3 * b * x + sp.sin(a - x) / (b + 1),
        (a - b) ** 2 + sp.Rational(3, 2) * x**3 - x + 7,
    ]
    for _ in range(2):  # the second time from the cache
        for e in exprs:
            assert NumPy().doprint(e) == NumPyPrinter().doprint(e)
            assert Mpmath().doprint(e) == MpmathPrinter().doprint(e)


def test_a_kept_printing_is_the_printers_own_for_its_roots_and_floats():
    root = x ** sp.Rational(1, 3)
    e = 2 * root + a
    with_root = Scalar([("_root0", x, 3)])
    assert with_root.doprint(e) == "a + 2*_root0"
    # the same expression by a printer without that root: not the kept text
    assert Scalar().doprint(e) == PythonCodePrinter().doprint(e) == "a + 2*x**(1/3)"
    assert with_root.doprint(e) == "a + 2*_root0"
    # Floats of other precisions print with their own digits (not kept at all)
    low, high = a * sp.Float(3.25, 2), a * sp.Float(3.25, 40)
    assert NumPyPrinter().doprint(low) != NumPyPrinter().doprint(high)
    for _ in range(2):
        assert NumPy().doprint(low) == NumPyPrinter().doprint(low)
        assert NumPy().doprint(high) == NumPyPrinter().doprint(high)
    # re(...) is still rewritten as SymPy's doprint does
    r = sp.re(sp.Symbol("z")) + 1
    assert NumPy().doprint(r) == NumPyPrinter().doprint(r) == "numpy.real(z) + 1"


def test_the_fits_factored_forms_are_sympys_factor():
    n = sp.Symbol("n_h", positive=True)
    for degree in (1, 3, 8):
        D, Q = fit._cofactors(degree, n)
        H = fit._hilbert_inverse(degree + 1)
        for j in range(degree + 1):
            p = sum((Q[k] * H[j, k] for k in range(degree + 1)), 0 * D)
            for poly in (p, D):
                assert sp.srepr(fit._factored(poly)) == sp.srepr(sp.factor(poly.as_expr()))
    m = sp.Symbol("m", positive=True)  # a generator that is not a symbol: factor itself
    poly = sp.Poly(4 * m**2 + 4 * m, 2 * m)
    assert fit._factored(poly) == sp.factor(poly.as_expr())


def _largest_at_50_digits(n, degree):
    """The index ``fit.scaled_error`` picked before: every value compared at 50 digits."""
    d = fit.scaled_coefficients(degree, n)
    s = fit.s
    err = s**n - sum(c * s**k for k, c in enumerate(d))
    u = sp.Symbol("u", nonnegative=True)
    slope = n * u ** max(n.p - n.q, 0) - sp.diff(err + s**n, s).subs(s, u**n.q) * u ** max(
        n.q - n.p, 0
    )
    stationary = sp.Poly(sp.expand(slope), u)
    roots = [sp.Integer(0), sp.Integer(1)]
    if not stationary.is_zero:
        roots += [r for r in stationary.real_roots() if 0 < r < 1]
    values = [err.subs(s, r**n.q) for r in roots]
    k = max(range(len(values)), key=lambda i: abs(sp.N(values[i], 50)))
    return err, roots, values, k


def test_the_largest_fit_error_is_the_one_compared_at_50_digits():
    for n, degrees in ((sp.Rational(3, 2), (2, 5)), (sp.Rational(7, 3), (3,))):
        for degree in degrees:
            err, roots, values, k = _largest_at_50_digits(n, degree)
            assert fit._largest(err, roots, n.q, values) == k
            assert fit.scaled_error(degree, n).max_abs == sp.Abs(values[k])
    # an exact fit (X2^1 by a line): every error is 0, a tie, and the first wins
    err, roots, values, k = _largest_at_50_digits(sp.Integer(1), 2)
    assert set(values) == {0} and fit._largest(err, roots, 1, values) == k == 0


def test_kept_simplify_and_factor_results_are_sympys():
    e = (x**2 - a**2) / (x - a) + sp.sin(b) ** 2 + sp.cos(b) ** 2
    assert memo.simplify(e) == sp.simplify(e) == x + a + 1
    assert memo.simplify(e) is memo.simplify(e)
    assert memo.factor(x**2 - a**2) == (x - a) * (x + a)
