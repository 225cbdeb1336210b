"""The laws as input (derive/laws.py): the registry's interface and the consistency of the laws.

* The generated interface: ``OPTIONS``, ``OPTION_DEFAULTS``, ``OPTION_DOCS``,
  ``LAW_PARAMETERS``, ``LAW_UNITS``, each parameter's ``law``, and every generated
  function's option table, all from the one registry.
* Stribeck's and static_kinetic's laws with ``mu_k = mu_s`` are Coulomb's, and Hunt-Crossley's with
  ``n_h = 3/2`` is Hertz-Damp, in every generated function that takes the option.

Error model of the consistency checks. The mpmath variants at 30 digits compute the
exact value of each function to ~25 digits (a few hundred operations on terms of
the size of the result or ~1e3 times it): the two laws, equal in exact arithmetic,
must agree there to ``1e-20`` relative (absolute below 1). The numpy variants are
roundings of that value: the second law's numpy error against it must not exceed
four times the first law's, or, where that is zero, 16 ulps of ``max(1, |value|)``
(the terms at this state are of order 1 to 10 and cancel in some outputs, as
``1 - 2 acos/pi`` of Eq. 23 does): the new law's expressions lose no accuracy
against the paper's.
"""

import importlib
import inspect
import itertools

import mpmath
import numpy as np
import pytest

from beltmdsm.derive import laws
from beltmdsm.derive.units import contact_units
from beltmdsm.generated import (
    _support,
    correlation,
    dynamics,
    fit,
    friction,
    hybrid,
    stability,
    unforced,
)
from beltmdsm.generated.parameters import (
    BASE,
    CONTACT_LAWS,
    FRICTION_LAWS,
    KNOWN,
    LAW_PARAMETERS,
    LAW_UNITS,
    OPTION_DEFAULTS,
    OPTION_DOCS,
    OPTIONS,
    PARAMETERS,
    TENSION_LAWS,
)

MODULES = (unforced, dynamics, fit, friction, stability, correlation, hybrid)
EPS = np.finfo(float).eps
#: One state per positional argument name (in contact, sliding backwards, Vb = 3).
ARGS = dict(
    t=0.7, X1=0.3, Y1=1.2, X2=0.9, Y2=-0.4, sgn=-1.0, Vr=-3.0, Vhat=8.5, mu_s=0.4, Vb=3.0,
    X2max=2.0, u=-4.0, V=6.0, N0=9.81, N1=3.0, theta=0.7, z=0.1, v=-0.2, phi=0.3, psi=1.1,
)  # fmt: skip


def test_options_are_the_registry():
    for option in laws.OPTIONS:
        assert OPTIONS[option] == laws.choices(option)
        assert OPTION_DEFAULTS[option] == OPTIONS[option][0] == laws.default(option)
        assert set(OPTION_DOCS[option]) == set(OPTIONS[option])
        assert all(OPTION_DOCS[option][c] == laws.get(option, c).summary for c in OPTIONS[option])
    assert (FRICTION_LAWS, CONTACT_LAWS, TENSION_LAWS) == tuple(OPTIONS.values())
    assert OPTION_DEFAULTS == {"friction": "coulomb", "contact": "hertz_damp", "tension": "allowed"}


def test_every_law_parameter_is_in_the_table_with_its_owner_and_in_base():
    owner = {p["name"]: p["law"] for p in PARAMETERS}
    assert len(owner) == len(PARAMETERS)  # one row per name, shared ones too
    for (option, choice), names in LAW_PARAMETERS.items():
        assert choice in OPTIONS[option]
        for name in names:
            # the row's owner is the first law that lists the name (registry order)
            first = next(key for key, listed in LAW_PARAMETERS.items() if name in listed)
            assert owner[name] == first and name in BASE and name in KNOWN
    assert LAW_PARAMETERS[("friction", "stribeck")] == ("mu_k", "v_s")
    assert LAW_PARAMETERS[("friction", "static_kinetic")] == ("mu_k",)  # shared
    assert LAW_PARAMETERS[("contact", "hunt_crossley")] == ("n_h",)
    assert LAW_PARAMETERS[("friction", "coulomb")] == ()
    assert {n for names in LAW_PARAMETERS.values() for n in names} == {
        n for n, o in owner.items() if o is not None
    }
    assert (BASE["mu_k"], BASE["v_s"], BASE["n_h"]) == (0.25, 1.0, 1.5)


def test_units_are_derived_from_the_contact_law():
    assert LAW_UNITS[("contact", "hertz_damp")] == {
        "beta2": "1/m^(5/4)",
        "omega2": "rad/(m^(1/4) s)",
    }
    assert LAW_UNITS[("contact", "kelvin_voigt")] == {"beta2": "1", "omega2": "rad/s"}
    assert LAW_UNITS[("contact", "hunt_crossley")] == {
        "beta2": "1/m^((n_h + 1)/2)",
        "omega2": "rad m^((1 - n_h)/2)/s",
    }
    units = {p["name"]: p["unit"] for p in PARAMETERS}
    assert units["beta2"] == "1/m^(5/4)" == contact_units("hertz_damp")["beta2"]


def _option_tables():
    """``(module, function, options, table)`` for every generated function with options."""
    for m in MODULES:
        for name in m.__all__:
            fn = getattr(m, name)
            if not callable(fn) or name.startswith("bind_"):
                continue
            sig = inspect.signature(fn)
            options = [
                p
                for p, q in sig.parameters.items()
                if q.kind is q.KEYWORD_ONLY and p not in ("vhat_model", "backend")
            ]
            if options:
                yield m, name, options, getattr(m, "_" + name.upper())


def test_every_law_option_offers_exactly_the_registrys_choices():
    seen = set()
    for m, name, options, table in _option_tables():
        for i, option in enumerate(options):
            if option in OPTIONS:
                seen.add(option)
                assert {key[i] for key in table} == set(OPTIONS[option]), (m.__name__, name)
                assert (
                    inspect.signature(getattr(m, name)).parameters[option].default
                    == (OPTION_DEFAULTS[option])
                )
    assert seen == set(OPTIONS)


def test_a_missing_law_parameter_is_named():
    without = {k: v for k, v in BASE.items() if k != "v_s"}
    assert np.isfinite(unforced.equilibrium(**without)[0])  # Coulomb's law does not need it
    with pytest.raises(TypeError, match="'v_s'"):
        unforced.equilibrium(friction="stribeck", **without)
    with pytest.raises(TypeError, match="'n_h'"):
        fit.coefficients(1.0, contact="hunt_crossley")
    listed = ", ".join(map(repr, FRICTION_LAWS))  # every registered law, in order
    with pytest.raises(ValueError, match=f"friction must be one of {listed}; got 'no_such_law'"):
        unforced.equilibrium(friction="no_such_law", **BASE)


def test_a_function_refuses_a_law_without_the_property_it_needs():
    with pytest.raises(_support.Unsupported, match="stribeck.*closed_form_average"):
        stability.critical_belt_speed(friction="stribeck", **BASE)
    with pytest.raises(ValueError, match="no elementary antiderivative"):
        stability.unstable_interval(friction="stribeck", **BASE)
    assert np.isfinite(stability.growth_rate(friction="stribeck", **BASE))  # not refused


# Stribeck with mu_k = mu_s is Coulomb; Hunt-Crossley with n_h = 3/2 is Hertz-Damp -------


def _calls(option):
    """``(label, name, module, args, other options)`` per function taking ``option``."""
    for m, name, options, table in _option_tables():
        if option not in options:
            continue
        fn = getattr(m, name)
        pos = [
            p
            for p, q in inspect.signature(fn).parameters.items()
            if q.kind is q.POSITIONAL_OR_KEYWORD
        ]
        keep = [o for o in options if o != option]
        others = sorted({tuple((o, k) for o, k in zip(options, key) if o in keep) for key in table})
        modes = (-1.0, 0.0, 1.0, 2.0, 3.0) if "mode" in pos else (None,)
        for other, mode in itertools.product(others, modes):
            args = [mode if p == "mode" else ARGS[p] for p in pos]
            label = f"{m.__name__.split('.')[-1]}.{name}{dict(other)}{'' if mode is None else mode}"
            yield label, name, m, args, dict(other)


def _evaluate(fn, args, params, **options):
    try:
        with np.errstate(all="ignore"):
            return fn(*args, **options, **params)
    except _support.Unsupported as err:
        return err


def _flat(value, mp=False):
    if isinstance(value, Exception):
        return value
    if mp:
        if isinstance(value, mpmath.matrix):
            return [value[i, j] for i in range(value.rows) for j in range(value.cols)]
        return list(value) if isinstance(value, (list, tuple)) else [value]
    return np.asarray(value, dtype=complex).ravel()


def _same_function(label, m, name, args, params_a, params_b, opts_a, opts_b):
    """The error model of the module docstring, for one function and two law choices."""
    positional = _positional(m, name)
    keep = {k: v for k, v in params_a.items() if k not in positional}
    keep_b = {k: v for k, v in params_b.items() if k not in positional}
    a = _flat(_evaluate(getattr(m, name), args, keep, **opts_a))
    b = _flat(_evaluate(getattr(m, name), args, keep_b, **opts_b))
    mp_module = importlib.import_module(f"beltmdsm.generated.mp.{m.__name__.split('.')[-1]}")
    with mpmath.workdps(30):
        mp_args = [mpmath.mpf(x) for x in args]
        ref_a = _flat(_evaluate(getattr(mp_module, name), mp_args, keep, **opts_a), mp=True)
        ref_b = _flat(_evaluate(getattr(mp_module, name), mp_args, keep_b, **opts_b), mp=True)
    if isinstance(a, Exception) or isinstance(b, Exception):
        # a refusal is the same for both or for the new law only where the property
        # it needs is the law's own (checked in test_a_function_refuses...)
        assert isinstance(b, Exception), label
        return
    assert len(ref_a) == len(ref_b) == a.size == b.size, label
    for x, y, ra, rb in zip(a, b, ref_a, ref_b):
        ra, rb = complex(ra), complex(rb)
        if not np.isfinite(ra):
            assert x == y or (np.isnan(x) and np.isnan(y)), label
            continue
        assert abs(ra - rb) <= 1e-20 * max(1.0, abs(ra)), label
        err_a, err_b = abs(x - ra), abs(y - ra)
        assert err_b <= max(4 * err_a, 16 * EPS * max(1.0, abs(ra))), (label, err_a, err_b)


def _positional(m, name):
    sig = inspect.signature(getattr(m, name))
    return {p for p, q in sig.parameters.items() if q.kind is q.POSITIONAL_OR_KEYWORD}


@pytest.mark.parametrize("case", list(_calls("friction")), ids=lambda c: c[0])
def test_stribeck_with_equal_coefficients_is_coulomb(case):
    label, name, m, args, other = case
    params = {**BASE, "mu_k": BASE["mu_s"]}
    _same_function(
        label, m, name, args, params, params, {**other, "friction": "coulomb"},
        {**other, "friction": "stribeck"},
    )  # fmt: skip


@pytest.mark.parametrize("case", list(_calls("friction")), ids=lambda c: c[0])
def test_static_kinetic_with_equal_coefficients_is_coulomb(case):
    """mu_k = mu_s: the static bound equals the slip coefficient, and every generated
    function (stick surfaces, saltation matrices, averages) is Coulomb's."""
    label, name, m, args, other = case
    params = {**BASE, "mu_k": BASE["mu_s"]}
    _same_function(
        label, m, name, args, params, params, {**other, "friction": "coulomb"},
        {**other, "friction": "static_kinetic"},
    )  # fmt: skip


@pytest.mark.parametrize("case", list(_calls("contact")), ids=lambda c: c[0])
def test_hunt_crossley_with_exponent_three_halves_is_hertz_damp(case):
    label, name, m, args, other = case
    params = {**BASE, "n_h": 1.5}
    _same_function(
        label, m, name, args, params, params, {**other, "contact": "hertz_damp"},
        {**other, "contact": "hunt_crossley"},
    )  # fmt: skip


# Capabilities: the structural facts, decided by SymPy, recorded per combination --------


def test_capabilities_cover_every_combination_with_every_fact():
    from beltmdsm.generated import capabilities

    combos = set(itertools.product(FRICTION_LAWS, CONTACT_LAWS, TENSION_LAWS))
    assert set(capabilities.CAPABILITIES) == combos
    assert capabilities.FACTS == tuple(capabilities.FACT_DOCS)
    for key, facts in capabilities.CAPABILITIES.items():
        assert tuple(facts) == capabilities.FACTS, key
        for name, (holds, reason) in facts.items():
            assert isinstance(holds, bool) and reason and "\n" not in reason, (key, name)


#: The facts of the laws shipped when this test was written; a law added later is checked
#: by the implications of `test_capabilities_agree_with_the_laws_values` only.
SHIPPED_FACTS = {
    "coulomb": dict(slip=True, monotone=True, closed=True),
    "stribeck": dict(slip=False, monotone=False, closed=False),
    # slips at a constant mu_k, but its static bound mu_s jumps down to it at Vr = 0
    "static_kinetic": dict(slip=True, monotone=False, closed=True),
}
SHIPPED_CONTACTS = ("hertz_damp", "kelvin_voigt", "hunt_crossley")


def _mu(law, speeds):
    """``mu(s)`` at the base set, read from the unforced equilibrium X1 = mu(Vb) g / omega1^2."""
    p = {k: v for k, v in BASE.items() if k != "Vb"}
    X1 = unforced.equilibrium(friction=law, Vb=np.asarray(speeds), **p)[0]
    return X1 * p["omega1"] ** 2 / p["g"]


def test_capabilities_of_the_shipped_laws():
    from beltmdsm.generated import capabilities

    for key, facts in capabilities.CAPABILITIES.items():
        if key[0] not in SHIPPED_FACTS or key[1] not in SHIPPED_CONTACTS:
            continue  # a law registered by another test
        holds = {name: h for name, (h, _) in facts.items()}
        expected = SHIPPED_FACTS[key[0]]
        assert holds["one_way_coupling"], key
        assert holds["slip_friction_state_independent"] == expected["slip"], key
        assert holds["friction_monotone"] == expected["monotone"], key
        assert holds["closed_form_average"] == expected["closed"], key
    jump = capabilities.CAPABILITIES[("static_kinetic", "kelvin_voigt", "clipped")]
    assert "falling jump at Vr = 0" in jump["friction_monotone"][1]
    assert "mu_k < mu_s" in jump["friction_monotone"][1]
    stribeck = capabilities.CAPABILITIES[("stribeck", "hertz_damp", "clipped")]
    assert "X1'" in stribeck["slip_friction_state_independent"][1]
    assert "0 < |Vr| < oo" in stribeck["friction_monotone"][1]
    assert "mu_k < mu_s" in stribeck["friction_monotone"][1]
    assert "Risch" in stribeck["closed_form_average"][1]


@pytest.mark.parametrize("law", FRICTION_LAWS)
def test_capabilities_agree_with_the_laws_values(law):
    """Every registered friction law: a fact that holds implies what the law's values at
    the base set show (mu read from the generated unforced equilibrium), and a law whose
    average is a quadrature has a quadrature in generated/friction.py, a closed form none."""
    import inspect as _inspect

    from beltmdsm.generated import capabilities

    facts = capabilities.CAPABILITIES[(law, CONTACT_LAWS[0], TENSION_LAWS[0])]
    holds = {name: h for name, (h, _) in facts.items()}
    speeds = np.linspace(1e-3, 20.0, 401)
    mu = _mu(law, speeds)
    if holds["slip_friction_state_independent"]:
        assert np.ptp(mu) <= 1e-12 * max(1.0, abs(mu).max()), law
    if holds["friction_monotone"]:
        assert mu[0] >= 0 and np.all(np.diff(mu) >= -1e-12 * abs(mu).max()), law
    quadrature = "_support.quad(" in _inspect.getsource(friction._MU_BAR[(law,)].impl)
    assert quadrature == (not holds["closed_form_average"]), law
    if not holds["closed_form_average"]:
        assert "quadrature" in facts["closed_form_average"][1], law


def _bind_cases():
    for m in (dynamics, hybrid):
        for name in m.__all__:
            if not name.startswith("bind_"):
                continue
            public = getattr(m, name[5:])
            options = inspect.signature(getattr(m, name)).parameters
            if "friction" not in options and "contact" not in options:
                continue
            table = getattr(m, "_" + name[5:].upper())
            keys = [o for o in options if o not in ("backend", "params")]
            for key in table:
                chosen = dict(zip(keys, key))
                if chosen.get("friction") == "stribeck" or chosen.get("contact") == "hunt_crossley":
                    yield pytest.param(m, name, public, chosen, id=f"{name}{key}")


@pytest.mark.parametrize("m,name,public,options", list(_bind_cases()))
def test_bound_kernels_of_the_new_laws_equal_their_public_functions(m, name, public, options):
    """Each bound scalar kernel of Stribeck's and Hunt-Crossley's laws (plain Python)
    against its public function, both against the mpmath variant: the kernel's error is
    at most four times the public function's, or 16 ulps of max(1, |value|) (the same
    expressions; only libm and numpy round their elementary functions differently)."""
    from beltmdsm.generated._support import NoVariant

    if isinstance(getattr(m, "_" + name[5:].upper())[tuple(options.values())], NoVariant):
        return
    params = {**BASE, "n_h": 1.7, "mu_k": 0.2}
    pos = [
        p
        for p, q in inspect.signature(public).parameters.items()
        if q.kind is q.POSITIONAL_OR_KEYWORD
    ]
    for mode in (-1.0, 0.0, 1.0, 2.0) if "mode" in pos else (None,):
        args = [mode if p == "mode" else ARGS[p] for p in pos]
        try:
            bound = getattr(m, name)(**options, backend="python", **params)
        except ValueError:  # a switch no run takes (no saltation variant)
            return
        got = np.ravel(np.asarray(bound(*args), dtype=float))
        with np.errstate(all="ignore"):
            ref_np = np.ravel(np.asarray(public(*args, **options, **params), dtype=float))
        mp_module = importlib.import_module(f"beltmdsm.generated.mp.{m.__name__.split('.')[-1]}")
        with mpmath.workdps(30):
            exact = _flat(
                getattr(mp_module, name[5:])(*map(mpmath.mpf, args), **options, **params), mp=True
            )
        for g, r, e in zip(got, ref_np, exact):
            e = float(e)
            assert abs(g - e) <= max(4 * abs(r - e), 16 * EPS * max(1.0, abs(e))), (name, mode)
