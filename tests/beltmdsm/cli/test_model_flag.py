"""``--model NAME`` through the command line (``python -m beltmdsm``, run in the test's
process: tests/inprocess.py): the other models run on the generic runtime with their own
parameters and states, each number against a reference typed here; every command that
runs the paper's model only refuses them in one line."""

import json
import math

import numpy as np
import pytest
from inprocess import cli as _cli
from scipy.optimize import brentq

#: reference_two_dof's base set in hoffmann's names (tests/beltmdsm/oscillator/).
HOFFMANN = ["--k1", "1.25", "--k2", "0.25", "--k3", "0.5", "--k_c", "1", "--F_pre", "1"]
HOFFMANN += ["--c1", "0.05", "--c2", "0.05", "--Vb", "1"]


def _json(*argv):
    done = _cli(*argv, "--json")
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def test_belt_1dof_hopf_point_is_the_closed_form():
    out = _json(
        "branch", "--model", "belt_1dof", "--friction", "stribeck", "--param", "Vb",
        "--from", "0.5", "--to", "5",
    )  # fmt: skip
    p = out["params"]
    typed = p["v_s"] * math.log(
        p["g"] * (p["mu_s"] - p["mu_k"]) / (2 * p["beta1"] * p["omega1"] * p["v_s"])
    )
    assert out["model"] == "belt_1dof" and out["states"] == ["x", "x_dot"]
    assert out["hopf_points"] == pytest.approx([typed], abs=1e-10)
    # the cycles born there: unstable pure slip (subcritical) up to the stick onset,
    # docs/modelling.md's 2.900393 (checked against the paper's model in
    # tests/beltmdsm/oscillator/test_oscillator_cycles.py), where the cycle grazes v_r = 0
    (born,) = out["cycle_branches"]
    assert born["criticality"] == "subcritical" and born["side"] == 1
    assert born["stick_onset"] == pytest.approx(2.900393, abs=1e-6)
    last = born["cycles"][-1]
    assert last["state"]["x_dot"] == pytest.approx(born["stick_onset"], abs=1e-9)
    assert all(not c["stable"] for c in born["cycles"])


def test_belt_1dof_stick_slip_cycle_is_the_closed_form():
    out = _json(
        "floquet", "--model", "belt_1dof", "--friction", "static_kinetic", "--Vb", "0.5",
        "--beta1", "0",
    )  # fmt: skip
    p = out["params"]
    # undamped: slip from the stick end x_e = mu_s g / w^2 around x_k = mu_k g / w^2 on
    # a circle of the phase plane back to x' = Vb (2 pi - 2 phi) / w later, then stick
    # from x_k - u0 back to x_e
    w, Vb = p["omega1"], p["Vb"]
    u0 = (p["mu_s"] - p["mu_k"]) * p["g"] / w**2
    typed = (2 * math.pi - 2 * math.atan2(u0 * w, Vb)) / w + 2 * u0 / Vb
    assert out["autonomous"] and out["kind"] == "stick_slip" and out["sticks"] == 1
    assert out["period"] == pytest.approx(typed, rel=1e-10)
    assert out["state"] == pytest.approx({"x": p["mu_s"] * p["g"] / w**2, "x_dot": Vb})


def test_belt_1dof_forced_response_is_den_hartogs():
    # x'' + x = a cos(W t) - F sgn(x'): the paper's force alpha_t W^2 sin(W t + pi/2)
    r, U, a = 0.8, 0.3, 1.0
    out = _json(
        "floquet", "--model", "belt_1dof", "--Vb", "0", "--beta1", "0", "--mu_s",
        repr(U * a / 9.81), "--alpha_t", repr(a / r**2), "--Omega_t", repr(r),
        "--phase_t", repr(math.pi / 2),
    )  # fmt: skip
    assert not out["autonomous"] and out["sticks"] == 0 and len(out["switches"]) == 2
    assert out["period"] == pytest.approx(2 * math.pi / r, rel=1e-14)
    # the turning point (x' = 0, a reversal) lies at Den Hartog's amplitude
    x, v = out["state"]["x"], out["state"]["x_dot"]
    t_turn = out["switches"][0]["t"]
    amplitude = math.sqrt(1 / (1 - r * r) ** 2 - (U * math.tan(math.pi / (2 * r)) / r) ** 2)
    # the free motion x'' + x = a cos(r t) - F s from (x, v) at 0, s = sgn(v), to t_turn
    s, C = math.copysign(1.0, v), a / (1 - r * r)
    A, B = x - C + U * a * s, v
    turn = A * math.cos(t_turn) + B * math.sin(t_turn) + C * math.cos(r * t_turn) - U * a * s
    assert abs(turn) == pytest.approx(amplitude * a, rel=1e-8)


def _typed_jacobian(p, mu):
    K = np.array([[p["k1"] + p["k3"] / 2, p["k3"] / 2], [p["k3"] / 2, p["k2"] + p["k3"] / 2]])
    K_eff = K + np.array([[0.0, -mu * p["k_c"]], [0.0, p["k_c"]]])
    C = np.diag([p["c1"], p["c2"]])
    return np.block([[np.zeros((2, 2)), np.eye(2)], [-K_eff / p["m"], -C / p["m"]]])


def test_hoffmann_flutter_threshold_and_cycle():
    out = _json(
        "branch", "--model", "hoffmann", *HOFFMANN, "--param", "mu_s", "--from", "0.01",
        "--to", "1",
    )  # fmt: skip
    p = out["params"]

    def growth(mu):
        return np.linalg.eigvals(_typed_jacobian(p, mu)).real.max()

    assert out["model"] == "hoffmann" and out["states"] == ["x", "y", "x_dot", "y_dot"]
    assert out["hopf_points"] == pytest.approx([brentq(growth, 0.01, 1.0, xtol=1e-15)], abs=1e-10)
    assert [row["stable"] for row in out["steady_sliding"]][::2] == [True, False]
    cycle = _json("floquet", "--model", "hoffmann", *HOFFMANN, "--mu_s", "0.4")
    assert cycle["kind"] == "stick_slip" and cycle["state"]["x_dot"] == pytest.approx(1.0)
    assert set(cycle["state"]) == {"x", "y", "x_dot", "y_dot"} and len(cycle["multipliers"]) == 3
    # [re, im] pairs, as the paper's floquet writes them; the stick's multiplier is 0
    assert min(math.hypot(*m) for m in cycle["multipliers"]) < 1e-10
    assert math.hypot(*cycle["trivial_multiplier"]) == pytest.approx(1.0, abs=1e-9)


def test_simulate_names_the_models_states(tmp_path):
    out = _json("simulate", "--model", "hoffmann", "--mu_s", "0.8", "--t-end", "20",
                "--save", str(tmp_path / "run.npz"))  # fmt: skip
    assert out["model"] == "hoffmann" and out["status"] == "done"
    assert list(out["final"]) == ["x", "y", "x_dot", "y_dot"] == out["states"]
    saved = np.load(tmp_path / "run.npz")
    assert set(saved.files) == {"t", "modes", "x", "y", "x_dot", "y_dot"}
    assert saved["t"][-1] == 20.0 and saved["y"][-1] == out["final"]["y"]
    text = _cli("simulate", "--model", "belt_1dof", "--t-end", "5")
    assert text.returncode == 0 and "x_dot" in text.stdout and "X1" not in text.stdout


def test_another_models_parameter_is_refused_for_the_paper():
    done = _cli("simulate", "--k_c", "2", "--t-end", "1")
    assert done.returncode == 2 and done.stdout == ""
    assert "argument --k_c: a parameter of --model hoffmann, not of the paper's model" in (
        done.stderr
    )


@pytest.mark.parametrize(
    "argv, said",
    [
        # sweep and lyapunov run another model since issue 39's last items: what they
        # still refuse is what applies to the paper's model only, and the other commands
        (["sweep", "--param", "Vb", "--values", "1", "--continue", "up"], "argument --continue"),
        (["floquet-band", "--param", "Vb", "--from", "1", "--to", "2"], "does not run model"),
        (["predict"], "the MDSM split"),
        (["lyapunov", "--perturbation", "0.1"], "argument --perturbation: moves the start"),
        (["simulate", "--png", "{tmp}/x.png"], "argument --png: applies to the paper's model"),
        (["simulate", "--beta2", "0.1"], "argument --beta2: not a parameter of model"),
        (["floquet", "--contact", "kelvin_voigt"], "argument --contact: applies to the paper"),
        (["floquet", "--friction", "stribeck", "--v_s", "-1"], "must be > 0; got -1"),
    ],
)
def test_what_another_model_lacks_is_refused_in_one_line(argv, said, tmp_path):
    argv = [a.format(tmp=tmp_path) for a in argv]
    done = _cli(argv[0], "--model", "belt_1dof", *argv[1:])
    assert done.returncode == 2 and done.stdout == ""
    assert said in done.stderr and len(done.stderr.strip().splitlines()) == 1
    assert "error: argument --" in done.stderr
