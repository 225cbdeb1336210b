"""Coordinates with their own units (issue 39: "masses with a rotational degree of freedom").

A model entry names the unit of a coordinate (`Oscillator.units`, ``m`` by default); its
module says each state's unit (``STATE_UNITS``) and the runtime's labels, tables and JSON
read it. The how-to's second worked example (docs/howto/own_model.md: a carriage ``x`` [m]
carrying a disc ``theta`` [rad] whose rim touches the belt, ``v_r = x' + r theta' - Vb``)
is derived here into a temporary folder, never registered nor shipped, and checked
against its equations typed by hand:

    m x'' + c_x x' + k_x x = F,    J theta'' + c_t theta' + k_t theta = r F,
    slip: F = -mu(|v_r|) sgn(v_r) F_n;  stick: F = lambda keeps v_r' = 0, i.e.
    lambda (1/m + r^2/J) = (c_x x' + k_x x)/m + r (c_t theta' + k_t theta)/J.
"""

import csv
import doctest
import importlib.util
import json
import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from beltmdsm import Model, plotting, state_names
from beltmdsm.derive.models import dimensions, entries, get, register
from beltmdsm.derive.models.registry import check
from beltmdsm.derive.models.render import render_entry
from beltmdsm.generated.models import MODELS, load
from beltmdsm.oscillator import System, load_model, simulate, steady_sliding
from beltmdsm.oscillator.sweep import sweep

ROOT = Path(__file__).resolve().parents[3]
HOWTO = ROOT / "docs" / "howto" / "own_model.md"


def _example_entry():
    """The how-to's rotational entry, run where the page says to put it (the namespace of
    derive/models/entries.py), its `register` call caught: this process's registry (and
    so generated/models/) stays the shipped one."""
    blocks = re.findall(r"```python\n(.*?)```", HOWTO.read_text(encoding="utf-8"), re.S)
    (code,) = [b for b in blocks if '"theta"' in b]
    caught = []
    exec(code, {**vars(entries), "register": lambda option, e: caught.append((option, e))})  # noqa: S102
    ((option, entry),) = caught
    assert option == "model"
    return entry


@pytest.fixture(scope="module")
def wheel(tmp_path_factory):
    """The example's numeric module, derived (checked as `register` checks it) and
    written to a temporary folder, then imported from there."""
    entry = _example_entry()
    check(entry)
    path = tmp_path_factory.mktemp("derived") / f"{entry.name}.py"
    path.write_text(render_entry(entry), encoding="utf-8")
    spec = importlib.util.spec_from_file_location(entry.name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


# ---- the entry and its module


def test_the_entry_names_its_units_and_the_module_holds_them(wheel):
    entry = _example_entry()
    assert entry.coordinate_units == ("m", "rad")
    assert entry.state_units == ("m", "rad", "m/s", "rad/s")
    assert wheel.STATES == ("x", "theta", "x_dot", "theta_dot")
    assert wheel.STATE_UNITS == ("m", "rad", "m/s", "rad/s")
    assert load_model(wheel) is wheel and wheel.NAME not in MODELS


def test_the_shipped_models_are_in_metres():
    """Every shipped entry leaves `units` out: its states are m and m/s, as before."""
    for name in MODELS:
        module = load(name)
        assert get(name).units is None
        expected = tuple("m" if s in module.COORDINATES else "m/s" for s in module.STATES)
        assert module.STATE_UNITS == state_names.units(name) == expected
        if name != "paper":
            assert Model(model=name).state_units == expected


@pytest.mark.parametrize(
    ("unit", "rate"), [("m", "m/s"), ("rad", "rad/s"), ("1", "1/s"), ("N m/rad", "(N m/rad)/s")]
)
def test_a_rate_is_in_its_coordinates_unit_per_second(unit, rate):
    assert dimensions.rate_unit(unit) == rate


def test_a_modal_amplitude_enters_through_its_mode_shape():
    """A dimensionless modal coordinate ``a`` moves the contact point by ``phi a``: the
    mode shape's value ``phi`` [m] makes its term a speed; without it, 1/s is refused."""
    import sympy as sp

    phi = sp.Symbol("phi")
    units = {"a": "1", "x": "m"}
    assert dimensions.slip_mismatch({"a": phi, "x": 1}, units, {phi: "m"}, "m/s") is None
    assert "the term of a' is in 1/s" in dimensions.slip_mismatch({"a": 1}, units, {}, "m/s")
    # units the check cannot read leave the term unchecked, not passed as right
    assert dimensions.slip_mismatch({"a": phi}, units, {phi: "mm"}, "m/s") is None
    assert dimensions.parse("m+s") is None and dimensions.parse("N m s/rad") is not None


def test_the_dimension_examples_run():
    result = doctest.testmod(dimensions, optionflags=doctest.ELLIPSIS)
    assert result.attempted > 0 and result.failed == 0, result


# ---- the registry refuses what it can tell is wrong, in one line


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (dict(units={"phi": "rad"}), "units: 'phi' is not a coordinate ('x', 'theta')"),
        (dict(units={"theta": ""}), "units: 'theta' needs a one-line unit string"),
        (dict(units={"theta": "rad\nm"}), "units: 'theta' needs a one-line unit string"),
        (dict(units=["rad"]), "units: a mapping of coordinate -> unit"),
    ],
)
def test_register_refuses_a_unit_that_is_no_coordinates(change, message):
    entry = replace(_example_entry(), name="wheel_copy", **change)
    with pytest.raises(ValueError, match=re.escape(message)) as err:
        register("model", entry)
    assert "\n" not in str(err.value) and str(err.value).startswith("model 'wheel_copy'")


def test_register_refuses_a_slip_form_without_the_lever_arm():
    """``v_r = x' + theta' - Vb`` adds rad/s to m/s: refused, naming the term."""
    e = _example_entry()
    contact = replace(e.contact, slip=lambda P: {"x": 1, "theta": 1})
    with pytest.raises(ValueError, match=re.escape("contact.slip: the term of theta' is in 1/s")):
        register("model", replace(e, name="wheel_copy", contact=contact))
    # a length on the angle's term: m^2/s, refused too
    contact = replace(e.contact, slip=lambda P: {"x": 1, "theta": P["r"] ** 2})
    with pytest.raises(ValueError, match=re.escape("theta' is in m**2/s")):
        check(replace(e, name="wheel_copy", contact=contact))
    # the lever arm on a length: the carriage's term is m^2/s
    contact = replace(e.contact, slip=lambda P: {"x": P["r"], "theta": P["r"]})
    with pytest.raises(ValueError, match=re.escape("the term of x' is in m**2/s")):
        check(replace(e, name="wheel_copy", contact=contact))


def test_a_unit_the_check_cannot_read_is_not_checked():
    """``deg`` is outside the check's words: the slip form is taken as given (the page
    says so), and the unit still reaches the module."""
    e = replace(_example_entry(), name="wheel_copy", units={"theta": "deg"})
    check(e)
    assert e.state_units == ("m", "deg", "m/s", "deg/s")


# ---- the runtime reads the units


def test_the_loader_checks_state_units(wheel):
    """A module's STATE_UNITS is one unit string per state (a module typed by hand may
    leave it out: m and m/s)."""
    import types

    bad = types.ModuleType("bad")
    for name in ("NAME", "COORDINATES", "STATES", "UNILATERAL", "FRICTION_LAWS"):
        setattr(bad, name, getattr(wheel, name))
    for name in ("PARAMETERS", "DEFAULTS", "EXCITATION", "SURFACES", "kernels"):
        setattr(bad, name, getattr(wheel, name))
    assert state_names.module_units(bad) == ("m", "m", "m/s", "m/s")
    bad.STATE_UNITS = ("m", "rad", "m/s")
    with pytest.raises(ValueError, match="STATE_UNITS must be one unit string per state"):
        load_model(bad)


def test_the_units_reach_labels_csv_and_json(wheel, tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    s = System(wheel, friction="static_kinetic", Vb=1.0)
    assert state_names.units(s) == s.units == ("m", "rad", "m/s", "rad/s")
    run = simulate(s, 2.0)
    ax = plotting.simulation(run)
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("t [s]", "x_dot [m/s]")
    assert plotting.simulation(run, variable="theta_dot").get_ylabel() == "theta_dot [rad/s]"
    assert plotting.simulation(run, variable="theta").get_ylabel() == "theta [rad]"
    assert plotting.observable_label("theta_max", s) == "theta max [rad]"
    assert plotting.observable_label("theta_dot_amplitude", s) == "theta_dot amplitude [rad/s]"
    # the slip velocity stays the contact's, in the unit of Vb
    assert plotting.observable_label("max_abs_v_r", s) == "max |v_r| [m/s]"
    assert plotting.observable_label("v_r_min", s) == "v_r min [m/s]"
    # JSON: the model's part names each state's unit; a sweep each column's
    result = sweep(s, "Vb", [1.0], t_end=4.0, t_discard=1.0)
    out = json.loads(json.dumps(result.as_dict()))
    assert out["state_units"] == {"x": "m", "theta": "rad", "x_dot": "m/s", "theta_dot": "rad/s"}
    assert out["units"]["Vb"] == "m/s" and out["units"]["theta_min"] == "rad"
    assert out["units"]["theta_dot_final"] == "rad/s" and "regime" not in out["units"]
    # CSV: the headers with their units where asked, the plain names otherwise
    result.to_csv(tmp_path / "u.csv", units=True)
    head = next(csv.reader((tmp_path / "u.csv").open()))
    assert head[:2] == ["model", "Vb [m/s]"]
    assert {"theta_min [rad]", "theta_dot_max [rad/s]", "x_final [m]", "regime"} <= set(head)
    result.to_csv(tmp_path / "plain.csv")
    rows = list(csv.DictReader((tmp_path / "plain.csv").open()))
    assert float(rows[0]["theta_final"]) == result.rows[0]["theta_final"]


def test_the_paper_keeps_its_labels():
    """Nothing the paper's model shows changes: its columns and units."""
    assert plotting.STATE == {"X1": ("m", 0), "X1'": ("m/s", 1), "X2": ("m", 2), "X2'": ("m/s", 3)}
    assert plotting.observable_label("X1'_amplitude") == "X1' amplitude [m/s]"


def test_the_models_page_gives_each_states_unit():
    spec = importlib.util.spec_from_file_location(
        "beltmdsm_site", ROOT / "docs" / "_ext" / "beltmdsm_site.py"
    )
    site = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(site)
    page = site.models_page()
    assert "* states: ``X1`` [m], ``Y1`` [m/s], ``X2`` [m], ``Y2`` [m/s]" in page
    assert "* states: ``x`` [m], ``y`` [m], ``x_dot`` [m/s], ``y_dot`` [m/s]" in page


# ---- the derived example against its equations typed by hand


def _typed(p, friction):
    """M, C, K, d = w and the steady-sliding Jacobian (mode -1: F = mu(-v_r) F_n, so
    dF/dv_r = -mu'(Vb) F_n; Stribeck: mu' = -(mu_s - mu_k)/v_s exp(-v/v_s))."""
    M = np.diag([p["m"], p["J"]])
    C = np.diag([p["c_x"], p["c_t"]])
    K = np.diag([p["k_x"], p["k_t"]])
    w = np.array([1.0, p["r"]])
    Vb, Fn = p["Vb"], p["F_n"]
    assert friction == "stribeck"
    mu = p["mu_k"] + (p["mu_s"] - p["mu_k"]) * np.exp(-Vb / p["v_s"])
    dmu = -(p["mu_s"] - p["mu_k"]) / p["v_s"] * np.exp(-Vb / p["v_s"])
    q = np.linalg.solve(K, w * mu * Fn)
    Mi = np.linalg.inv(M)
    J = np.block([[np.zeros((2, 2)), np.eye(2)], [-Mi @ K, -Mi @ (C + dmu * Fn * np.outer(w, w))]])
    return q, J


@pytest.mark.parametrize("Vb", [1.0, 3.0, 6.0])  # unstable, unstable, stable
def test_steady_sliding_and_its_eigenvalues_against_numpy(wheel, Vb):
    s = System(wheel, friction="stribeck", Vb=Vb)
    q, J = _typed(s.params, "stribeck")
    eq = steady_sliding(s)
    assert eq.mode == -1
    # the closed form x = mu(Vb) F_n / k_x, theta = r mu(Vb) F_n / k_t: a few roundings
    np.testing.assert_allclose(eq.state[:2], q, rtol=1e-14)
    assert np.all(eq.state[2:] == 0.0)
    typed = np.linalg.eigvals(J)
    key = lambda z: (round(z.real, 9), z.imag)  # noqa: E731
    np.testing.assert_allclose(sorted(eq.eigenvalues, key=key), sorted(typed, key=key), atol=1e-12)
    # the derived characteristic polynomial and Hurwitz determinants
    k = wheel.kernels("stribeck")
    a = k.characteristic(s.p)
    np.testing.assert_allclose(a, np.poly(J), rtol=1e-12, atol=1e-13)
    assert eq.stable == bool(np.all(typed.real < 0)) == bool(np.all(k.hurwitz(s.p) > 0))


def _reference(p, t_end):
    """The stick-slip run from rest by solve_ivp with events, typed from the equations:
    slip back (v_r < 0, F = mu_k F_n) until v_r = 0, then stick (F = lambda) while
    lambda <= mu_s F_n; switch times and the end state."""
    m, J, r, kx, kt, cx, ct = (p[k] for k in ("m", "J", "r", "k_x", "k_t", "c_x", "c_t"))
    Fn, Vb, mus, muk = p["F_n"], p["Vb"], p["mu_s"], p["mu_k"]

    def field(z, F):
        return [z[2], z[3], (-cx * z[2] - kx * z[0] + F) / m, (-ct * z[3] - kt * z[1] + r * F) / J]

    def holding(z):
        return (
            m
            * J
            / (J + m * r * r)
            * ((cx * z[2] + kx * z[0]) / m + r * (ct * z[3] + kt * z[1]) / J)
        )

    def slip(t, z):
        return field(z, muk * Fn)

    def stick(t, z):
        return field(z, holding(z))

    to_stick = lambda t, z: z[2] + r * z[3] - Vb  # noqa: E731
    to_stick.terminal, to_stick.direction = True, 1
    to_slip = lambda t, z: abs(holding(z)) - mus * Fn  # noqa: E731
    to_slip.terminal, to_slip.direction = True, 1
    t, z, mode, events = 0.0, np.zeros(4), -1, []
    while t < t_end:
        fun, ev = (slip, to_stick) if mode == -1 else (stick, to_slip)
        sol = solve_ivp(
            fun, (t, t_end), z, method="DOP853", rtol=1e-12, atol=1e-12, events=ev, max_step=0.01
        )
        t, z = sol.t[-1], sol.y[:, -1].copy()
        if sol.status != 1:
            break
        events.append((t, mode, 0 if mode == -1 else -1))
        if mode == -1:
            assert abs(holding(z)) <= mus * Fn, "a reversal: not in this reference"
            mode = 0
        else:
            assert holding(z) > 0, "a slip forward: not in this reference"
            mode = -1
    return z, events


def test_a_stick_slip_run_against_solve_ivp(wheel):
    s = System(wheel, friction="static_kinetic", Vb=1.0)
    run = simulate(s, 25.0, rtol=1e-12, atol=1e-12)
    z, events = _reference(s.params, 25.0)
    assert run.status == "done" and len(events) >= 6
    assert [(b, a) for _, b, a in run.switches] == [(b, a) for _, b, a in events]
    assert np.allclose([t for t, _, _ in run.switches], [t for t, _, _ in events], atol=1e-8)
    assert np.allclose(run.y[:, -1], z, atol=1e-8)


def test_the_command_line_names_the_units():
    """Another model's JSON names each state's unit (``state_units``) and a sweep each
    column's (``units``); the text gives each range its unit (tests/inprocess.py: the
    command in this process)."""
    from inprocess import cli

    def run(*argv):
        done = cli(*argv)
        assert done.returncode == 0, done.stderr[-2000:]
        return done.stdout

    text = run("simulate", "--model", "hoffmann", "--t-end", "1")
    assert "y in [" in text and re.search(r"y_dot in \[[^]]*\] m/s$", text.strip())
    out = json.loads(run("sweep", "--model", "belt_1dof", "--param", "Vb", "--values", "1",
                         "--t-end", "4", "--no-cache", "--json"))  # fmt: skip
    assert out["state_units"] == {"x": "m", "x_dot": "m/s"}
    assert out["units"] == {
        "Vb": "m/s", "x_min": "m", "x_max": "m", "x_dot_min": "m/s", "x_dot_max": "m/s",
        "x_final": "m", "x_dot_final": "m/s",
    }  # fmt: skip
