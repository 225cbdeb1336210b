"""The code generator: up to date, deterministic, detects hand edits, SymPy-free imports."""

import inspect
import math
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import hand_eq4 as H
import mpmath
import numpy as np
import pytest
import sympy as sp
from checkout import as_checkout

from beltmdsm.derive.codegen import printers
from beltmdsm.generated import _support
from beltmdsm.generated import dynamics as _dynamics
from beltmdsm.generated import hybrid as _hybrid
from beltmdsm.generated import oscillator as _osc
from beltmdsm.generated.parameters import BASE, DOMAINS, FRICTION_LAWS

ROOT = Path(__file__).resolve().parents[2]


def _run(args, cwd=ROOT, seed="0", **kw):
    env = {**os.environ, "PYTHONHASHSEED": seed, "PYTHONDONTWRITEBYTECODE": "1"}
    return subprocess.run(
        [sys.executable, *args], cwd=cwd, env=env, capture_output=True, text=True, **kw
    )


#: The hand edit of the copy that `derivations` checks: one line of one file, and a file
#: that no derivation produces.
EDITED = ("g*mu_s/omega1**2", "g*mu_s/omega1**3")


#: The derivations `start_derivations` started when the session began, if it did
#: (tests/conftest.py, when a test that reads `derivations` is selected).
STARTED = {}


def start_derivations(folder):
    """Start the two derivations that the three tests below read (each a minute of SymPy
    in a process of its own), at once, writing into ``folder``; the processes.

    * ``"root"``: ``python -m derive --check`` in this checkout, ``PYTHONHASHSEED=0``;
    * ``"edited"``: the same in a copy of derive/ and generated/ (`as_checkout`) with
      generated/unforced.py edited by hand (`EDITED`) and a stray file leftover.py in generated,
      ``PYTHONHASHSEED=4242``.

    tests/conftest.py starts them when the session's tests are collected, so that on a
    machine of two cores they run beside the rest of the suite; else `derivations` does.
    """
    copy = folder / "checkout"
    for part in ("derive", "generated"):
        shutil.copytree(ROOT / part, copy / part, ignore=shutil.ignore_patterns("__pycache__"))
    as_checkout(copy)  # beside a link to beltmdsm/, the copies are beltmdsm.derive/.generated
    target = copy / "generated" / "unforced.py"
    text = target.read_text()
    assert text.count(EDITED[0]) >= 1
    target.write_text(text.replace(*EDITED, 1))
    (copy / "generated" / "leftover.py").write_text("x = 1\n")
    runs = {}
    for name, cwd, seed in (("root", ROOT, "0"), ("edited", copy, "4242")):
        env = {**os.environ, "PYTHONHASHSEED": seed, "PYTHONDONTWRITEBYTECODE": "1"}
        out, err = (open(folder / f"{name}.{s}", "w+") for s in ("out", "err"))
        cmd = [sys.executable, "-m", "derive", "--check"]
        proc = subprocess.Popen(cmd, cwd=cwd, env=env, stdout=out, stderr=err, text=True)
        runs[name] = (proc, out, err)
    return runs


def stop_derivations(runs):
    """Kill what is still running of ``runs`` and close its files."""
    for proc, out, err in runs.values():
        if proc.poll() is None:
            proc.kill()
            proc.wait()
        out.close()
        err.close()


@pytest.fixture(scope="module")
def derivations(tmp_path_factory):
    """`start_derivations`' two runs, finished: each ``(returncode, stdout, stderr)``."""
    runs = STARTED.pop("derivations", None) or start_derivations(tmp_path_factory.mktemp("derive"))
    done = {}
    try:
        for name, (proc, out, err) in runs.items():
            code = proc.wait()  # a minute each on an idle machine, many under load
            out.seek(0)
            err.seek(0)
            done[name] = (code, out.read(), err.read())
    finally:
        stop_derivations(runs)
    return done


def test_generated_is_up_to_date(derivations):
    code, out, err = derivations["root"]
    assert code == 0, out + err
    assert "up to date" in out


def test_output_is_identical_across_hash_seeds(derivations):
    """The derivation at ``PYTHONHASHSEED=0`` equals generated/ byte for byte
    (`test_generated_is_up_to_date`); at 4242 it equals the edited copy of generated/
    in every file but the two edited ones, and in the edited one it differs by the
    edited line alone: both seeds derive the same files."""
    code, out, err = derivations["root"]
    assert code == 0, out + err
    code, out, err = derivations["edited"]
    assert code == 1, out + err
    stale = re.findall(r"^STALE (generated/\S+?):", out, flags=re.M)
    assert sorted(stale) == ["generated/leftover.py", "generated/unforced.py"], out
    assert "2 generated file(s) differ" in err
    diff = out.split("STALE generated/unforced.py:", 1)[1].split("STALE ", 1)[0]
    changed = [
        line
        for line in diff.splitlines()
        if line[:1] in ("+", "-") and not line.startswith(("+++", "---"))
    ]
    assert len(changed) == 2, diff
    assert changed[0].startswith("-") and EDITED[1] in changed[0], diff
    assert changed[1].startswith("+") and EDITED[0] in changed[1], diff
    assert changed[0][1:].replace(*EDITED[::-1], 1) == changed[1][1:], diff


def test_check_names_a_hand_edited_file(derivations):
    code, out, err = derivations["edited"]
    assert code == 1
    assert "STALE generated/unforced.py" in out
    assert "omega1**3" in out  # the diff is shown
    assert "generated/leftover.py" in out


def test_every_generated_file_has_the_do_not_edit_header():
    for path in (ROOT / "generated").rglob("*.py"):
        head = path.read_text().splitlines()[:2]
        assert head[0].startswith("# Generated by `python -m derive`"), path
        assert "DO NOT EDIT" in head[1], path


@pytest.mark.parametrize(
    "module",
    [
        "beltmdsm.generated.unforced",
        "beltmdsm.generated.dynamics",
        "beltmdsm.generated.mp.unforced",
        "beltmdsm.generated.mp.dynamics",
    ],
)
def test_importing_generated_code_does_not_import_sympy(module):
    code = f"import sys, {module}; print('sympy' in sys.modules)"
    assert _run(["-c", code]).stdout.strip() == "False"


@pytest.mark.parametrize(
    "module", ["beltmdsm.generated.stability", "beltmdsm.generated.mp.stability"]
)
def test_importing_generated_code_does_not_import_numba(module):
    """numba is loaded on the first accelerated call, not at import (it takes a while)."""
    code = f"import sys, {module}; print('numba' in sys.modules)"
    assert _run(["-c", code]).stdout.strip() == "False"


@pytest.mark.parametrize(
    "exponent", ["1/3", "2/3", "4/3", "10/3", "14/3", "-1/3", "-4/3", "-2/3", "1/6", "7/4"]
)
@pytest.mark.parametrize("printer", ["NumPy", "Scalar"])
def test_fractional_powers_print_through_hoisted_roots(exponent, printer):
    """b**(n/d) (d >= 3) prints as powers of one root per base, with the value of the power."""
    g, w = sp.symbols("g omega2", positive=True)
    x = sp.Symbol("x", real=True)
    e = sp.Rational(exponent)
    expr = 3 * g**e * w ** (2 * e) / (1 + w**e) + x**e
    roots = printers.hoisted_roots([expr])
    expected = {(g, e.q), (w, e.q), (w, (2 * e).q)} if e.q >= 3 else set()
    assert {(b, d) for _, b, d in roots} == {bd for bd in expected if bd[1] >= 3}
    assert all(b != x for _, b, _ in roots)  # x is not provably >= 0
    text = getattr(printers, printer)(roots).doprint(expr)
    left = re.findall(r"(\w+)\*\*\(-?\d+/(\d+)\)", text)  # powers printed as such
    assert all(base == "x" or int(d) == 2 for base, d in left), text
    values = {"g": 9.81, "omega2": 1.7, "x": 0.3}
    namespace = {**values, "numpy": np, "math": math}
    namespace.update(
        {name: float(mpmath.mpf(values[str(b)]) ** (mpmath.mpf(1) / d)) for name, b, d in roots}
    )
    exact = sp.N(
        expr.subs({g: sp.Float("9.81", 30), w: sp.Float("1.7", 30), x: sp.Float("0.3", 30)}), 30
    )
    # Python floats (libm's pow, < 1 ulp in glibc; numpy's and numba's loops are not
    # involved), roots rounded once: the larger term of the worst case (14/3) takes five
    # powers and about ten roundings, ~11 eps = 2.5e-15
    assert float(eval(text, namespace)) == pytest.approx(float(exact), rel=4e-15)


# Bound scalar kernels (bind_<name>) ------------------------------------------------------

BIND_MODULES = (_dynamics, _hybrid, _osc)
BIND = [
    (module, name) for module in BIND_MODULES for name in module.__all__ if name.startswith("bind_")
]
BIND_IDS = [f"{module.__name__.split('.')[-1]}.{name}" for module, name in BIND]
EPS = np.finfo(float).eps
#: State arguments of the public functions, drawn at random (X2 on both sides of 0).
STATE_DRAW = {
    "t": lambda r: r.uniform(-5, 5),
    "X1": lambda r: r.normal() * 2,
    "Y1": lambda r: r.normal() * 3,
    "X2": lambda r: r.uniform(-1, 3),
    "Y2": lambda r: r.normal() * 2,
    "sgn": lambda r: float(r.choice([-1, 0, 1])),
    "mode": lambda r: float(r.choice([-1, 0, 1, 2, 3])),
    "tau": lambda r: r.uniform(0, 30),
    "z": lambda r: r.normal() * 2,
    "v": lambda r: r.normal() * 3,
    "X1_0": lambda r: r.normal() * 2,
    "Y1_0": lambda r: r.normal() * 3,
    "zf_0": lambda r: r.normal(),
    "vf_0": lambda r: r.normal() * 2,
    "z_0": lambda r: r.normal() * 2,
    "v_0": lambda r: r.normal() * 3,
    "zf": lambda r: r.normal(),
    "vf": lambda r: r.normal() * 2,
}


def test_every_bind_function_is_public_with_a_public_twin():
    assert len(BIND) >= 15
    for module, name in BIND:
        assert name[5:] in module.__all__, name
        assert callable(getattr(module, name[5:]))


def state_names(public):
    return [
        k
        for k, v in inspect.signature(public).parameters.items()
        if v.kind == v.POSITIONAL_OR_KEYWORD
    ]


def option_sets(public):
    """Every option combination a function takes (saltation: each switch of TRANSITIONS)."""
    kw = {k for k, v in inspect.signature(public).parameters.items() if v.kind == v.KEYWORD_ONLY}
    contacts = [{"contact": c} for c in ("hertz_damp", "kelvin_voigt")] if "contact" in kw else [{}]
    if "before" in kw:
        return [
            dict(c, before=b, after=a, surface=s)
            for c in contacts
            for b, a, s in _hybrid.TRANSITIONS
        ]
    if "tension" in kw:
        return [dict(c, tension=t) for c in contacts for t in ("allowed", "clipped")]
    return contacts


def bind_params(rng):
    p = {k: BASE[k] * float(np.exp(rng.uniform(-np.log(3), np.log(3)))) for k in BASE}
    p.update(
        alpha_n=p["alpha"] * rng.uniform(0.3, 2),
        Omega_n=p["Omega"] * rng.uniform(0.5, 2),
        phase_t=rng.uniform(-3, 3),
        phase_n=rng.uniform(-3, 3),
    )
    # the oscillator's damping on both sides of critical (beta1 = 1 exactly: see
    # test_bound_oscillator_kernels_at_critical_damping)
    p["beta1"] = float(rng.choice([rng.uniform(0, 0.99), rng.uniform(1.01, 4)]))
    return p


def entry_scale(name, state, options, p, ref):
    """The rounding scale of each output entry (tests/hand_eq4.py): the sum of the
    absolute values of its terms, with the rounding of the excitation's argument."""
    s = dict(state)
    x = [s.get(k, 0.0) for k in ("X1", "Y1", "X2", "Y2")]
    t, contact = s.get("t", 0.0), options.get("contact", "hertz_damp")
    if name == "rhs_branch":
        return H.rhs_scale(t, x, p, contact)
    if name == "normal_force":
        return H.force_scale(x[2], x[3], p, contact) if x[2] > 0 else 0.0
    if name == "normal_rhs":
        return H.rhs_scale(t, x, p, contact)[2:]
    if name == "normal_jacobian":
        return np.array(H.jacobian_scale(t, x, p, contact))[2:, 2:]
    if name == "free_acceleration":
        return H.a_free_scale(t, x[0], x[1], p)
    if name == "excitation":
        return H.excitation_scale(t, p)
    if name == "energy":
        return H.energy_scale(x, p, contact)
    if name == "power_balance":
        return H.power_scale(t, x, p, contact)
    if name == "vector_field":
        return H.field_scale(s["mode"], t, x, p, contact)
    if name == "mode_jacobian":
        return H.mode_jacobian_scale(s["mode"], t, x, p, contact)
    if name in ("surfaces", "surface_scales"):
        return H.surface_scales(t, x, p, contact)
    if name == "surface_rates":
        return H.rate_scale(s["mode"], t, x, p, contact)
    if name == "response_field":
        return H.response_field_scale(s["mode"], t, (s["z"], s["v"], x[2], x[3]), p, contact)
    if name == "saltation":
        return H.saltation_scale(
            options["before"], options["after"], options["surface"], t, x, p, contact
        )
    if name == "state_transition":  # (1 + omega1 tau) |Phi| (test_oscillator)
        return (1 + p["omega1"] * s["tau"]) * np.abs(ref).max()
    if name == "excitation_response":
        return H.response_scale(p, t)
    if name == "tangential_state":  # Phi's scale times the free part, plus the forced part
        tau, m = s["tau"], p["mu_s"] * abs(s["sgn"])
        Phi = np.abs(_osc.state_transition(tau, beta1=p["beta1"], omega1=p["omega1"]))
        free = [
            abs(s[x]) + abs(s[f]) + m * abs(s[r])
            for x, f, r in (("X1_0", "zf_0", "z_0"), ("Y1_0", "vf_0", "v_0"))
        ]
        forced = [abs(s["zf"]) + m * abs(s["z"]), abs(s["vf"]) + m * abs(s["v"])]
        return (1 + p["omega1"] * tau) * Phi.max() * sum(free) * (
            1 + p["omega1"] + 1 / p["omega1"]
        ) + np.array(forced)
    raise KeyError(name)


def compare_bound(module, name, backend, rng, draws):
    """The bound kernel against the public function at random scalar states.

    Error model: both evaluate the same expressions in the same order and are each
    within a few ulps of the entry's rounding scale (the sum of its terms' absolute
    values, hand_eq4) of the exact value (test_hybrid, test_tension, test_oscillator);
    they differ only where numpy's, Python's math (libm) and numba's (LLVM) elementary
    functions round differently, so by at most 16 ulps of that scale. Returns the
    largest difference in ulps of the scale."""
    public = getattr(module, name[5:])
    names = state_names(public)
    worst = 0.0
    for options in option_sets(public):
        for _ in range(draws):
            p = bind_params(rng)
            state = [STATE_DRAW[n](rng) for n in names]
            if module is _osc:  # the response from rest: t >= 0
                state = [abs(v) * 6 if n in ("t", "tau") else v for n, v in zip(names, state)]
            bound = getattr(module, name)(**options, backend=backend, **p)
            assert bound.backend == backend
            got = np.ravel(np.asarray(bound(*state), dtype=float))
            with np.errstate(divide="ignore", invalid="ignore"):
                ref = np.ravel(np.asarray(public(*state, **options, **p), dtype=float))
            assert got.shape == ref.shape, (name, options)
            scale = np.ravel(
                np.asarray(
                    entry_scale(name[5:], zip(names, state), options, H.full(p), ref), dtype=float
                )
            )
            err = np.abs(got - ref)
            assert np.all(err <= 16 * EPS * scale), (name, options, state, got, ref)
            with np.errstate(divide="ignore", invalid="ignore"):
                worst = max(worst, float(np.max(np.where(err > 0, err / (EPS * scale), 0))))
    return worst


@pytest.mark.parametrize("module,name", BIND, ids=BIND_IDS)
def test_bound_python_kernel_equals_the_public_function(rng, module, name):
    compare_bound(module, name, "python", rng, draws=3 if name == "bind_saltation" else 15)


@pytest.mark.parametrize("module,name", BIND, ids=BIND_IDS)
def test_bound_numba_kernel_equals_the_public_function(rng, module, name):
    pytest.importorskip("numba")
    compare_bound(module, name, "numba", rng, draws=2 if name == "bind_saltation" else 10)


@pytest.mark.parametrize("backend", ["python", "numba"])
@pytest.mark.parametrize("name", ["bind_state_transition", "bind_excitation_response"])
def test_bound_oscillator_kernels_at_critical_damping(name, backend):
    """beta1 = 1 exactly: the critically damped branch (the other two divide by
    sqrt(1 - beta1) = 0 and must not be evaluated). Same expressions: 16 ulps of the
    entries' scale, (1 + omega1 tau) |Phi| and the response's terms."""
    if backend == "numba":
        pytest.importorskip("numba")
    p = dict(BASE, beta1=1.0)
    bound = getattr(_osc, name)(backend=backend, **p)
    ref = np.ravel(getattr(_osc, name[5:])(0.7, **p))
    scale = entry_scale(name[5:], {"tau": 0.7, "t": 0.7}.items(), {}, H.full(p), ref)
    assert np.all(np.abs(np.ravel(bound(0.7)) - ref) <= 16 * EPS * np.asarray(scale))


def singular_point(case, backend):
    """(bound value, public value) where the public function divides by zero."""
    if case == "resonance":  # undamped resonance: NaN (test_oscillator)
        p = dict(BASE, beta1=0.0, Omega=BASE["omega1"])
        ref = np.ravel(_osc.excitation_response(0.7, **p))
        return _osc.bind_excitation_response(backend=backend, **p)(0.7), ref
    # grazing: the rate dh/dt = Y2 = 0 on entering contact; both evaluations divide by
    # it on purpose (numpy's kernel warns, numba's does not)
    kw = dict(before="flight", after="slip_back", surface="penetration", **BASE)
    with np.errstate(divide="ignore", invalid="ignore"):
        ref = np.ravel(_hybrid.saltation(0.0, 0.0, 1.0, 0.0, 0.0, **kw))
        got = _hybrid.bind_saltation(backend=backend, **kw)(0.0, 0.0, 1.0, 0.0, 0.0)
    return got, ref


@pytest.mark.parametrize("case", ["resonance", "grazing"])
def test_bound_numba_kernel_at_singular_points_gives_the_public_nan_or_inf(case):
    pytest.importorskip("numba")
    got, ref = singular_point(case, "numba")
    assert not np.all(np.isfinite(ref))
    np.testing.assert_array_equal(np.ravel(got), ref)


@pytest.mark.parametrize("case", ["resonance", "grazing"])
def test_bound_python_kernel_at_singular_points_gives_the_public_nan_or_inf(case):
    got, ref = singular_point(case, "python")
    np.testing.assert_array_equal(np.ravel(got), ref)


@pytest.mark.parametrize("module,name", BIND, ids=BIND_IDS)
def test_bound_kernel_exposes_its_raw_kernel_and_checked_parameters(module, name):
    p = dict(BASE, beta1=0.5, phase_t=0.25)
    bound = getattr(module, name)(backend="python", **p)
    assert isinstance(bound, _support.Bound) and bound.name == name[5:]
    assert repr(bound) == f"<bound {name[5:]} (python)>"
    full = {
        **p,
        "alpha_t": p["alpha"],
        "Omega_t": p["Omega"],
        "alpha_n": p["alpha"],
        "Omega_n": p["Omega"],
        "phase_n": 0.0,
    }
    assert bound.params == {k: full[k] for k in bound.params}
    assert all(type(v) is float for v in bound.args)
    n_state = len(state_names(getattr(module, name[5:])))
    state = [0.3, 0.1, 2.0, 1.3, -0.2, -1.0, 0.7, -0.4, 0.9, 1.1, -0.6, -1.0][:n_state]
    if name in ("bind_vector_field", "bind_surface_rates", "bind_response_field"):
        state[-1] = 1.0
    assert bound.kernel(*state, *bound.args) == bound(*state)


def used_parameters(module, name):
    return list(getattr(module, name)(backend="python", **BASE).params)


@pytest.mark.parametrize("module,name", BIND, ids=BIND_IDS)
def test_bind_rejects_bad_parameters_by_name(module, name):
    bind = getattr(module, name)
    used = used_parameters(module, name)
    assert used
    for param in used:
        bad_values = [float("nan"), float("inf"), np.array([1.0, 2.0])]
        if DOMAINS[param] != "real":
            bad_values.append(-1.0)
        for bad in bad_values:
            with pytest.raises(ValueError, match=f"'{param}'"):
                bind(backend="python", **{**BASE, param: bad})
    with pytest.raises(TypeError, match="'omega3'"):
        bind(backend="python", omega3=1.0, **BASE)
    with pytest.raises(ValueError, match="backend"):
        bind(backend="gpu", **BASE)
    options = [
        k
        for k, v in inspect.signature(bind).parameters.items()
        if v.kind == v.KEYWORD_ONLY and k != "backend"
    ]
    for option in options:
        with pytest.raises(ValueError, match=option):
            bind(backend="python", **{option: "nonsense"}, **BASE)
    missing = dict(BASE)
    del missing[used[0] if used[0] in missing else "alpha"]
    with pytest.raises(TypeError, match="missing"):
        bind(backend="python", **missing)


def test_bind_default_backend_is_numba_when_installed():
    numba = pytest.importorskip("numba")
    assert numba
    assert _dynamics.bind_energy(**BASE).backend == "numba"
    assert _dynamics.bind_energy(backend="python", **BASE).backend == "python"


# A law registered inside a test: adding a law is adding one entry --------------------

#: The viscous-plus-Coulomb law of docs/extending.md, registered in a fresh process
#: (before beltmdsm.derive.model builds its symbols), and three modules regenerated into a
#: temporary folder: nothing else in derive/ or generated/ is touched. Its name and
#: parameter are the test's own (toy_viscous, c_toy): a user who adds the docs' example
#: (viscous, c_v) to derive/laws.py keeps this test passing.
TOY_LAW = """
import sys
from pathlib import Path
from beltmdsm.derive import laws
from beltmdsm.derive.parameters import Parameter
laws.register(
    "friction",
    laws.FrictionLaw(
        "toy_viscous",
        "viscous plus Coulomb friction: mu(|Vr|) = mu_s + c_toy |Vr|",
        "Coulomb's static coefficient plus a viscous part.",
        "Eq. (3) for c_toy = 0",
        (Parameter("c_toy", "s/m", 0.02, "nonnegative", "viscous friction coefficient"),),
        coefficient=lambda P, s: P["mu_s"] + P["c_toy"] * s,
    ),
)
from beltmdsm.derive import codegen, modules
mods = (modules.unforced.build(), modules.friction.build(), modules.capabilities.build())
codegen.write(codegen.render_all(mods), Path(sys.argv[1]) / "generated")
"""

TOY_CHECK = """
import json, sys
sys.path.insert(0, sys.argv[1])
from beltmdsm.generated import capabilities, friction, unforced
from beltmdsm.generated.parameters import BASE, LAW_PARAMETERS, OPTIONS
p = {**BASE, "c_toy": 0.05, "Vb": 3.0}
Vr = [-9.0, -3.0, 0.5, 7.0]
print(json.dumps(dict(
    options=OPTIONS["friction"],
    owner=LAW_PARAMETERS[("friction", "toy_viscous")],
    base=BASE["c_toy"],
    X1=float(unforced.equilibrium(friction="toy_viscous", **p)[0]),
    J11=float(unforced.jacobian_at_equilibrium(friction="toy_viscous", **p)[1, 1]),
    critical=float(unforced.critical_belt_speed(friction="toy_viscous", **p)),
    mu_bar=[float(friction.mu_bar(v, 8.0, 0.4, friction="toy_viscous", c_toy=0.05)) for v in Vr],
    coulomb=[float(friction.mu_bar(v, 8.0, 0.4)) for v in Vr],
    facts=capabilities.CAPABILITIES[("toy_viscous", "hertz_damp", "allowed")],
)))
"""


def test_a_law_registered_in_a_test_is_derived_into_every_function(tmp_path):
    """The toy law's functions against closed forms typed here: X1^0 = (mu_s + c_toy Vb) g /
    omega1^2, the damping 2 beta1 omega1 + g c_toy of J^0 (no unforced boundary), the
    effective friction Eq. (23) + c_toy Vr (sgn(v) c_toy |v| = c_toy v averages to c_toy Vr: a
    closed form that SymPy's Risch algorithm finds, no quadrature), and its facts."""
    made = _run(["-c", TOY_LAW, str(tmp_path)])
    assert made.returncode == 0, made.stderr
    source = (tmp_path / "generated" / "friction.py").read_text()
    viscous = source[source.index("def _mu_bar__toy_viscous") :].split("\n\n\n")[0]
    assert "_support.quad(" not in viscous
    as_checkout(tmp_path)  # its generated/ is beltmdsm.generated there
    out = _run(["-c", TOY_CHECK, str(tmp_path)])
    assert out.returncode == 0, out.stderr
    got = __import__("json").loads(out.stdout)
    p = {**BASE, "c_toy": 0.05, "Vb": 3.0}
    assert got["options"] == [*FRICTION_LAWS, "toy_viscous"]  # the registry's, then the new law
    assert got["owner"] == ["c_toy"] and got["base"] == 0.02
    # a product and a quotient of rounded inputs: a few ulps
    X1 = (p["mu_s"] + p["c_toy"] * p["Vb"]) * p["g"] / p["omega1"] ** 2
    assert got["X1"] == pytest.approx(X1, rel=4 * EPS)
    damping = 2 * p["beta1"] * p["omega1"] + p["g"] * p["c_toy"]
    assert got["J11"] == pytest.approx(-damping, rel=4 * EPS)
    assert math.isnan(got["critical"])
    for v, mu_bar, coulomb in zip((-9.0, -3.0, 0.5, 7.0), got["mu_bar"], got["coulomb"]):
        assert mu_bar == pytest.approx(coulomb + 0.05 * v, abs=8 * EPS)
    facts = {k: holds for k, (holds, _) in got["facts"].items()}
    assert facts == {
        "slip_friction_state_independent": False,
        "one_way_coupling": True,
        "friction_monotone": True,
        "closed_form_average": True,
    }
    assert "toy_viscous" in got["facts"]["slip_friction_state_independent"][1]
