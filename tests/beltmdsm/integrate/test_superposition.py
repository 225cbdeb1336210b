"""The superposition integrator and the two scans for switches, against independent references."""

import numpy as np
import pytest

from beltmdsm.generated import hybrid, oscillator
from beltmdsm.integrate import _compiled, _dop853, normal, superposition
from beltmdsm.model import Model
from beltmdsm.simulation import simulate


def _line_kernels(offset):
    """X1 = t (a unit field); one surface h = (X1 - 1/2)^2 - offset, its rate 2 (X1 - 1/2)."""

    def field(t, X1, Y1, X2, Y2, mode):
        return (1.0, 0.0, 0.0, 0.0)

    def surfaces(t, X1, Y1, X2, Y2):
        return ((X1 - 0.5) ** 2 - offset,)

    def rates(t, X1, Y1, X2, Y2, mode):
        return (2.0 * (X1 - 0.5),)

    return field, surfaces, rates


@pytest.mark.parametrize("offset", [1e-2, 1e-6])
def test_dop853_finds_a_double_crossing_inside_one_step(offset):
    """h > 0 at both ends of the (single, exact) step, negative between: found, not stepped over."""
    field, surfaces, rates = _line_kernels(offset)
    advance = _compiled._python(_compiled._ADVANCE, (field, surfaces, rates))
    out = advance(
        (),
        (),
        (),
        -1.0,
        np.array([0]),
        np.array([-1.0]),
        0.0,
        np.zeros(4),
        1.0,
        1.0,
        1e-10,
        1e-10,
        np.inf,
    )
    status, n, *_, t_stop, y_stop, hit, _ = out
    assert status == _dop853.STATUS_EVENT and hit == 0 and n == 1
    assert t_stop == pytest.approx(0.5 - np.sqrt(offset), abs=1e-12)


def test_dop853_starting_on_its_surface_waits_until_inside():
    """A surface at zero at the start (the one just switched on) counts only once left."""
    field, surfaces, rates = _line_kernels(0.25)  # h(0) = 0, then < 0, then 0 at 1
    advance = _compiled._python(_compiled._ADVANCE, (field, surfaces, rates))
    out = advance(
        (),
        (),
        (),
        -1.0,
        np.array([0]),
        np.array([1.0]),
        0.0,
        np.zeros(4),
        2.0,
        0.1,
        1e-10,
        1e-10,
        np.inf,
    )
    status, *_, t_stop, _, hit, _ = out
    # direction +1: the event is h rising through 0 after being inside (h < 0): t = 1
    assert status == _dop853.STATUS_EVENT and t_stop == pytest.approx(1.0, abs=1e-12)


def test_dop853_matches_solve_ivp_on_a_smooth_mode():
    from scipy.integrate import solve_ivp

    def field(t, X1, Y1, X2, Y2, mode):
        return (Y1, -X1 - 0.1 * Y1 + np.sin(2 * t), Y2, -4 * X2)

    def surfaces(t, X1, Y1, X2, Y2):
        return (X1 - 10.0,)

    def rates(t, X1, Y1, X2, Y2, mode):
        return (Y1,)

    y0 = np.array([1.0, 0.0, 1.0, 0.0])
    advance = _compiled._python(_compiled._ADVANCE, (field, surfaces, rates))
    out = advance(
        (), (), (), 0.0, np.array([0]), np.array([1.0]), 0.0, y0, 20.0, 0.0, 1e-11, 1e-11, np.inf
    )
    status, n, ts, hs, ys, Fs, t_stop, y_stop, hit, _ = out
    assert status == _dop853.STATUS_END and t_stop == 20.0
    ref = solve_ivp(
        lambda t, y: field(t, *y, 0),
        (0, 20),
        y0,
        method="DOP853",
        rtol=1e-13,
        atol=1e-13,
        dense_output=True,
    )
    t = np.linspace(0, 20, 301)
    np.testing.assert_allclose(_dop853.evaluate(ts, hs, ys, Fs, t), ref.sol(t), atol=1e-9)


def _runs_kept():
    """The normal motions kept for runs of 40 s (the summary's Floquet check keeps the
    periodic normal orbit's too, keyed by its period)."""
    return [v for k, v in normal._KEEP.items() if k[1] == 40.0]


def test_normal_motion_cache_is_reused_and_cleared_without_changing_results():
    superposition.clear_cache()
    first = simulate(Model(Vb=4.0), solver="superposition", t_end=40.0)
    kept = _runs_kept()
    assert len(kept) == 1
    again = simulate(Model(Vb=6.0, mu_s=0.3), solver="superposition", t_end=40.0)
    assert _runs_kept() == kept  # neither Vb nor mu_s enters it
    simulate(Model(Vb=4.0, beta2=0.2), solver="superposition", t_end=40.0)
    assert len(_runs_kept()) == 2  # beta2 does
    superposition.clear_cache()
    assert not normal._KEEP
    np.testing.assert_array_equal(
        simulate(Model(Vb=4.0), solver="superposition", t_end=40.0).y, first.y
    )
    assert again.solver_used == "superposition"


def test_superposition_hands_over_at_undamped_resonance_with_a_reason():
    sim = simulate(
        Model(beta1=0.0, Omega=1.0, omega1=1.0), t_end=30.0, t_discard=10.0, solver="superposition"
    )
    assert sim.solver_used == "events"
    assert "undamped resonance" in sim.message


@pytest.mark.parametrize("backend", ["python", "numba"])
def test_compiled_and_python_scans_agree(backend):
    if backend == "numba":
        pytest.importorskip("numba")
    ref = simulate(
        Model(Vb=4.0), solver="superposition", t_end=30.0, backend="python", t_discard=10.0
    )
    run = simulate(
        Model(Vb=4.0), solver="superposition", t_end=30.0, backend=backend, t_discard=10.0
    )
    assert [k for _, k, _ in run.events] == [k for _, k, _ in ref.events]
    # the same arithmetic up to the math library's last bits (exp, sin, pow)
    np.testing.assert_allclose(run.y, ref.y, rtol=0, atol=1e-10)


def test_compiled_integrators_take_numbers_only_and_live_in_a_module_named_by_their_sources():
    """numba's disk cache: no dispatcher in a signature (it cannot be saved across
    processes), and a file name that changes with any source the code depends on."""
    pytest.importorskip("numba")
    f = _compiled.advance("vector_field", Model(), backend="numba")
    assert f.stem.startswith("beltmdsm_advance__vector_field__coulomb__hertz_damp__scalar_")
    g = _compiled.advance("vector_field", Model(friction="stribeck"), backend="numba")
    assert g.stem.startswith("beltmdsm_advance__vector_field__stribeck__hertz_damp__scalar_")
    assert _compiled._digest.cache_info().currsize >= 1
    digest = _compiled._digest.__wrapped__("0")
    assert digest != _compiled._digest.__wrapped__("1")  # numba's version counts
    simulate(Model(Vb=4.0), solver="events", t_end=20.0, t_discard=5.0, backend="numba")
    assert f.fn.__module__ == f.stem  # made at the first call, in the module of that name
    for signature in f.fn.signatures:
        assert all("Dispatcher" not in str(arg) for arg in signature)


@pytest.mark.parametrize("compiled", [True, False], ids=["compiled", "python"])
def test_normal_motion_at_one_time_is_its_dense_output(compiled, monkeypatch):
    from beltmdsm.integrate import _dop853
    from beltmdsm.integrate.normal import normal_motion
    from beltmdsm.model import Model

    m = Model()
    nm = normal_motion(m, 20.0, 1e-10, 1e-10, (m["g"] / 1.0, 0.0))
    if not compiled:
        monkeypatch.setattr(_dop853, "_evaluate_compiled", lambda: None)
    t = np.linspace(0.0, 20.0, 37)
    # the same polynomial of the same step, so the same bits whichever path runs
    np.testing.assert_array_equal(np.stack([nm.at(x) for x in t], axis=1), nm.evaluate(t))


def test_the_normal_key_holds_what_the_generated_kernels_take():
    """The key of the kept normal motions lists the parameters the bound kernels declare
    (their names found once per combination of laws), so that a change of any of them, and of
    nothing else, is a new normal motion."""
    for contact in ("hertz_damp", "kelvin_voigt", "hunt_crossley"):
        m = Model(Vb=3.0, beta1=0.2, contact=contact)
        used = hybrid.bind_response_field(contact=contact, backend="python", **m.params).params
        used |= oscillator.bind_excitation_response(backend="python", **m.params).params
        laws = ("coulomb", contact, "allowed")
        assert normal.normal_key(m) == (*laws, tuple(sorted(used.items())))
        assert normal.normal_key(m.replace(Vb=7.0, mu_s=0.1)) == normal.normal_key(m)
        assert normal.normal_key(m.replace(beta1=0.3)) != normal.normal_key(m)
