"""branch, floquet_band and floquet_map of another model's forced response (issue 39 item
4), each against a reference typed here: the linear oscillator's steady response in
closed form (Coulomb friction in pure slip is a constant force), a scipy solve_ivp
shooting of the Stribeck response, Den Hartog's non-stop motion, the stick onset by
bisection (brentq) on the closed form, and point-by-point floquet."""

import json
import math

import numpy as np
import pytest
from inprocess import cli
from scipy.integrate import solve_ivp
from scipy.optimize import brentq, fsolve

import beltmdsm
from beltmdsm import Model
from beltmdsm.errors import Unsupported
from beltmdsm.oscillator.hybrid import flow

G = 9.81


def linear_state(p, W):
    """The steady response at phase 0 of x'' + 2 b w x' + w^2 x = mu g + a W^2 sin(W t + f)
    (mode -1: the friction +mu g): x = mu g / w^2 + Im(A e^{iWt})."""
    w, b = p["omega1"], p["beta1"]
    A = p["alpha_t"] * W**2 * np.exp(1j * p["phase_t"]) / (w * w - W * W + 2j * b * w * W)
    return np.array([p["mu_s"] * p["g"] / w**2 + A.imag, W * A.real])


def test_coulomb_slip_branch_is_the_linear_closed_form():
    m = Model(model="belt_1dof", Vb=3.0, mu_s=0.1, alpha_t=0.5, Omega_t=2.0, phase_t=0.3)
    b = beltmdsm.branch(m, param="Omega_t", lo=1.9, hi=2.1)
    assert b.kind == "forced" and [s.kind for s in b.special] == ["range", "range"]
    assert b.points[0].value == 1.9 and b.points[-1].value == 2.1
    p = dict(b.system.params)
    worst = 0.0
    for point in b.points:
        ref = linear_state(p, point.value)
        worst = max(worst, float(np.max(np.abs(point.state - ref))))
        # the multipliers: exp(lambda T), lambda = -b w +- i w sqrt(1 - b^2)
        T = 2 * math.pi / point.value
        assert np.abs(point.multipliers) == pytest.approx([math.exp(-0.1 * T)] * 2, rel=1e-8)
        assert point.n_sticks == 0 and point.stable
    assert worst < 1e-8
    obs = b.points[0].observables()
    amp = abs(0.5 * 1.9**3 / (1 - 1.9**2 + 0.2j * 1.9))
    assert obs["x_dot_amplitude"] == pytest.approx(amp, rel=1e-8)


def _stribeck_shoot(p, W, guess):
    """Independent shooting: solve_ivp on the typed Stribeck field in backward slip."""

    def field(t, y):
        vr = y[1] - p["Vb"]
        mu = p["mu_k"] + (p["mu_s"] - p["mu_k"]) * math.exp(-abs(vr) / p["v_s"])
        force = p["alpha_t"] * W**2 * math.sin(W * t + p["phase_t"])
        w, b = p["omega1"], p["beta1"]
        return [y[1], -2 * b * w * y[1] - w * w * y[0] + force + mu * p["g"]]

    T = 2 * math.pi / W

    def P(x):
        return solve_ivp(field, (0, T), x, rtol=1e-13, atol=1e-13, method="DOP853").y[:, -1]

    x = fsolve(lambda x: P(x) - x, guess, xtol=1e-12)
    M = np.array([(P(x + 1e-6 * e) - P(x - 1e-6 * e)) / 2e-6 for e in np.eye(2)]).T
    return x, M


def test_stribeck_branch_against_solve_ivp_and_its_neimark_sacker_against_the_band():
    m = Model(model="belt_1dof", friction="stribeck", Vb=2.2, alpha_t=0.05, Omega_t=4.0)
    b = beltmdsm.branch(m, param="Vb", lo=1.8, hi=2.2)
    p = dict(b.system.params)
    for point in b.points[:: max(1, len(b.points) // 4)]:
        x, M = _stribeck_shoot({**p, "Vb": point.value}, 4.0, point.state)
        assert point.state == pytest.approx(x, abs=1e-8)
        assert sorted(np.abs(point.multipliers)) == pytest.approx(
            sorted(np.abs(np.linalg.eigvals(M))), abs=1e-6
        )
    (ns,) = [s for s in b.special if s.kind == "neimark_sacker"]
    # the multipliers of the points on either side cross the unit circle there
    below = max(q.value for q in b.points if q.value < ns.value)
    above = min(q.value for q in b.points if q.value > ns.value)
    assert not b.point_near(below).stable and b.point_near(above).stable
    assert ns.accuracy < 1e-6 and ns.stable_before is not ns.stable_after
    band = beltmdsm.floquet_band(m, "Vb", 1.8, 2.2, points=5, tol=1e-4)
    (edge,) = band.edges
    assert edge.kind == "neimark_sacker" and edge.bracket[0] <= ns.value <= edge.bracket[1]
    assert band.unstable == [[1.8, pytest.approx(ns.value, abs=1e-4)]]
    assert band.as_dict()["model"] == "belt_1dof" and "X1" not in json.dumps(band.as_dict())


def den_hartog_amplitude(r, U):
    """Den Hartog (1931), undamped: tests/beltmdsm/oscillator/test_oscillator_forced.py."""
    return math.sqrt(1 / (1 - r * r) ** 2 - (U * math.tan(math.pi / (2 * r)) / r) ** 2)


def test_den_hartog_non_stop_solution_along_the_branch():
    mu = 0.3 / G
    m = Model(model="belt_1dof", Vb=0.0, beta1=0.0, mu_s=mu, alpha_t=0.25, Omega_t=2.0,
              phase_t=math.pi / 2)  # fmt: skip
    b = beltmdsm.branch(m, param="Omega_t", lo=2.0, hi=2.2)
    assert len(b.points) >= 5
    for point in b.points:
        W = point.value
        a = 0.25 * W * W  # the force a cos(W t)
        assert point.n_reversals == 2 and point.n_sticks == 0
        turn = flow(point.system, 0.0, point.state, point.period, stop=lambda sw, n: True)
        assert abs(turn.y[0]) == pytest.approx(den_hartog_amplitude(W, mu * G / a) * a, rel=1e-9)


def test_stick_onset_is_located_against_the_closed_form():
    m = Model(model="belt_1dof", Vb=3.0, mu_s=0.1, alpha_t=0.7, Omega_t=0.7)
    b = beltmdsm.branch(m, param="Omega_t", lo=0.7, hi=1.1)
    (sl,) = [s for s in b.special if s.kind == "stick_onset"]
    # bisection on the closed form: the slip velocity's amplitude reaches Vb
    onset = brentq(lambda W: 0.7 * W**3 / abs(1 - W * W + 0.2j * W) - 3.0, 0.7, 1.0, xtol=1e-12)
    assert sl.value == pytest.approx(onset, abs=1e-7)
    assert b.points[-1].n_sticks == 1 and b.points[0].n_sticks == 0
    assert b.special[-1].kind == "range" and b.special[-1].value == 1.1
    band = beltmdsm.floquet_band(m, "Omega_t", 0.7, 1.1, points=3, tol=1e-4)
    (edge,) = band.edges
    assert edge.kind == "stick_onset" and edge.bracket[0] <= onset <= edge.bracket[1]
    assert edge.bracket[1] - edge.bracket[0] <= 1e-4 and band.unstable == []


def test_den_hartog_stick_onset_is_where_the_reversal_holds():
    """Below the onset the non-stop motion sticks at its turning points: there (x' = 0,
    x = -X, W t = psi) the holding force is a cos(psi) + w^2 X = W^2 X (with Den Hartog's
    X = -C cos(psi), C = a / (w^2 - W^2)), and stick holds once W^2 X <= F = mu g."""
    mu = 0.3 / G
    m = Model(model="belt_1dof", Vb=0.0, beta1=0.0, mu_s=mu, alpha_t=0.25, Omega_t=2.0,
              phase_t=math.pi / 2)  # fmt: skip
    b = beltmdsm.branch(m, param="Omega_t", lo=1.2, hi=2.0)
    (sl,) = [s for s in b.special if s.kind == "stick_onset"]

    def holding_minus_limit(W):
        a = 0.25 * W * W
        return W * W * den_hartog_amplitude(W, 0.3 / a) * a - 0.3

    onset = brentq(holding_minus_limit, 1.3, 1.4, xtol=1e-14)
    assert sl.value == pytest.approx(onset, abs=1e-9)
    assert "holding force at a slip reversal" in sl.detail
    assert b.point_near(1.25).n_sticks == 2 and b.point_near(1.9).n_reversals == 2


@pytest.mark.parametrize("periods", [1, 2])
def test_normal_load_modulation_branch_is_the_linear_closed_form(periods):
    """N = g - alpha_n W^2 sin(W t + f): in backward slip the friction +mu N is a force
    of the time alone, x = mu g / w^2 - Im(mu alpha_n W^2 e^{i(W t + f)} / (w^2 - W^2 +
    2 i b w W)); the response of 2 periods is the same orbit, its multipliers squared."""
    m = Model(model="belt_1dof", Vb=3.0, mu_s=0.2, alpha_n=0.5, Omega_n=1.5, phase_n=0.7)
    b = beltmdsm.branch(m, periods=periods, param="Omega_n", lo=1.45, hi=1.55)
    for point in b.points[::5]:
        W = point.value
        A = 0.2 * 0.5 * W * W * np.exp(0.7j) / (1 - W * W + 0.2j * W)
        ref = np.array([0.2 * G - A.imag, -W * A.real])
        assert point.state == pytest.approx(ref, abs=1e-8)
        T = periods * 2 * math.pi / W
        assert np.abs(point.multipliers) == pytest.approx([math.exp(-0.1 * T)] * 2, rel=1e-8)
    assert b.periods == periods and b.as_dict()["periods"] == periods


def test_floquet_map_against_point_by_point_floquet():
    m = Model(model="belt_1dof", friction="stribeck", Vb=2.2, alpha_t=0.05, Omega_t=4.0)
    fm = beltmdsm.floquet_map(m, "Vb", 1.9, 2.1, "beta1", 0.1, 0.11, points=2)
    assert [c.kind for c in fm.curves] == ["neimark_sacker"] and len(fm.curves[0].x) == 2
    for row, edges, x in zip(fm.rows, fm.unstable, fm.curves[0].x):
        assert edges == [[1.9, pytest.approx(x, abs=1e-3)]]
        for v, stable in ((x - 2e-3, False), (x + 2e-3, True)):
            f = beltmdsm.floquet(m.replace(Vb=v, beta1=float(row)))
            assert f.stable is stable
    assert fm.as_dict()["states"] == ["x", "x_dot"]


def test_an_unforced_model_still_refuses_by_name():
    for call in (
        lambda m: beltmdsm.branch(m, param="Vb", lo=1.0, hi=2.0),
        lambda m: beltmdsm.floquet_band(m, "Vb", 1.0, 2.0),
    ):
        with pytest.raises(Unsupported, match="without excitation"):
            call(Model(model="belt_1dof"))
    with pytest.raises(ValueError, match="reaches 0, where model 'belt_1dof' has no excitation"):
        beltmdsm.branch(Model(model="belt_1dof", alpha_t=0.1), param="alpha_t", lo=0, hi=0.2)
    with pytest.raises(Unsupported, match="backend='numba' applies to the paper's model"):
        beltmdsm.floquet_band(Model(model="belt_1dof", alpha_t=0.1), "Vb", 1, 2, backend="numba")


def test_the_commands_name_the_model_and_its_states(tmp_path):
    argv = ["--model", "belt_1dof", "--Vb", "3", "--mu_s", "0.1", "--alpha_t", "0.5"]
    png = tmp_path / "branch.png"
    done = cli("branch", *argv, "--Omega_t", "2", "--param", "Omega_t", "--from", "1.95",
               "--to", "2.05", "--json", "--png", str(png))  # fmt: skip
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)
    assert out["model"] == "belt_1dof" and out["states"] == ["x", "x_dot"]
    assert out["kind"] == "forced" and "X1" not in done.stdout and png.stat().st_size > 0
    first = out["points"][0]
    assert first["state0"] == pytest.approx(linear_state({**out["params"], "Omega_t": 1.95}, 1.95)
                                             .tolist(), abs=1e-8)  # fmt: skip
    done = cli("floquet-band", *argv, "--param", "Omega_t", "--from", "1.9", "--to", "2.1",
               "--points", "2", "--tol", "0.1", "--json")  # fmt: skip
    assert done.returncode == 0, done.stderr
    band = json.loads(done.stdout)
    assert band["model"] == "belt_1dof" and band["unstable"] == [] and len(band["grid"]) == 2
    done = cli("floquet-map", "--model", "belt_1dof", "--x", "Vb", "--x-from", "1",
               "--x-to", "2", "--y", "beta1", "--y-from", "0.1", "--y-to", "0.2")  # fmt: skip
    assert done.returncode == 2 and "floquet-map does not run model 'belt_1dof'" in done.stderr
    assert "without excitation" in done.stderr


def test_the_plot_names_the_models_observables():
    import matplotlib

    matplotlib.use("Agg")
    m = Model(model="belt_1dof", Vb=3.0, mu_s=0.1, alpha_t=0.7, Omega_t=0.9)
    b = beltmdsm.branch(m, param="Omega_t", lo=0.9, hi=1.0)
    ax = b.plot()
    assert ax.get_ylabel() == "x dot amplitude" and ax.get_xlabel() == "Omega_t"
    assert [t.get_text() for t in ax.texts] == ["SL"]
    table = b.to_pandas()
    assert list(table.columns[:3]) == ["Omega_t", "x", "x_dot"]
    with pytest.raises(ValueError, match="observable must be one of"):
        b.plot(observable="X1'_amplitude")
