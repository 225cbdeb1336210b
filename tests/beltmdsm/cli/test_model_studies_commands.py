"""``--model NAME`` on sweep, lyapunov, basins, responses, coexistence and
basin-stability (subprocess ``python -m beltmdsm``), each number against a closed form
typed here; the JSON and CSV name the model, the paper's JSON too."""

import csv
import json
import math
import subprocess
import sys

import pytest


def _cli(*argv, timeout=300):
    return subprocess.run(
        [sys.executable, "-m", "beltmdsm", *argv], capture_output=True, text=True, timeout=timeout
    )


def _json(*argv):
    done = _cli(*argv, "--json")
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


#: The 1-DOF belt's base set (generated/models/belt_1dof.py's DEFAULTS).
G, MU_S, MU_K, BETA, W = 9.81, 0.4, 0.25, 0.1, 1.0


def test_sweep_of_belt_1dof_meets_the_undamped_stick_slip_cycle(tmp_path):
    out_csv = tmp_path / "rows.csv"
    out = _json(
        "sweep", "--model", "belt_1dof", "--friction", "static_kinetic", "--beta1", "0",
        "--param", "Vb", "--values", "0.5", "1", "--t-end", "60", "--t-discard", "20",
        "--dt", "0.01", "--out", str(out_csv),
    )  # fmt: skip
    assert out["model"] == "belt_1dof" and out["states"] == ["x", "x_dot"]
    x_k, x_s = MU_K * G, MU_S * G
    for row in out["rows"]:
        R = math.hypot(x_s - x_k, row["Vb"])  # the slip circle's radius (w = 1)
        slack = R * 0.01**2 / 8 + 1e-9  # a sampled extremum's error
        assert row["regime"] == "stick_slip"
        assert abs(row["x_max"] - (x_k + R)) <= slack and abs(row["x_min"] - (x_k - R)) <= slack
        assert abs(row["x_dot_min"] + R) <= slack and row["x_dot_max"] == pytest.approx(row["Vb"])
    rows = list(csv.DictReader(out_csv.open()))
    assert [r["model"] for r in rows] == ["belt_1dof"] * 2
    assert float(rows[1]["x_max"]) == out["rows"][1]["x_max"]


def test_sweep_of_another_model_reads_its_points_back_from_the_cache(tmp_path):
    argv = ["sweep", "--model", "belt_1dof", "--param", "Vb", "--values", "1", "2"]
    argv += ["--t-end", "20", "--cache-dir", str(tmp_path)]
    first, again = _json(*argv), _json(*argv)
    assert (first["n_cached"], again["n_cached"]) == (0, 2)
    assert again["rows"] == first["rows"] and len(list(tmp_path.glob("*.json"))) == 2
    # another law is another point
    assert _json(*argv, "--friction", "stribeck")["n_cached"] == 0


def test_sweep_of_hoffmann_is_named_by_its_states():
    done = _cli(
        "sweep", "--model", "hoffmann", "--param", "k_c", "--values", "1", "2", "--t-end", "20"
    )
    assert done.returncode == 0, done.stderr
    assert "y_dot in [" in done.stdout and "X2" not in done.stdout and "X1" not in done.stdout
    done = _cli("sweep", "--model", "hoffmann", "--param", "alpha", "--values", "1")
    assert done.returncode == 2 and "argument --param: not a parameter of model 'hoffmann'" in (
        done.stderr
    )


def test_lyapunov_of_belt_1dof_removes_the_stick_direction():
    out = _json(
        "lyapunov", "--model", "belt_1dof", "--friction", "static_kinetic", "--Vb", "1",
        "--t-end", "60",
    )  # fmt: skip
    assert out["model"] == "belt_1dof" and out["collapsed"] == 1
    assert out["exponents"][1] is None  # -inf: the stick's direction
    assert abs(out["exponents"][0]) < 0.1  # the flow's own direction, over a few periods
    out = _json(
        "lyapunov", "--model", "belt_1dof", "--friction", "static_kinetic", "--Vb", "1",
        "--t-end", "60", "--start", "periodic",
    )  # fmt: skip
    assert out["start"] == "periodic" and out["collapsed"] == 1


def test_basins_and_responses_of_the_bistable_stribeck_belt():
    model = ["--model", "belt_1dof", "--friction", "stribeck", "--Vb", "2.5"]
    out = _json(
        "basins", *model, "--x-from", "1.5", "--x-to", "3.5", "--y-from", "-3", "--y-to",
        "0.5", "--points", "2", "--t-end", "600",
    )  # fmt: skip
    assert (out["model"], out["x"], out["y"]) == ("belt_1dof", "x", "x_dot")
    kinds = [a["kind"] for a in out["attractors"]]
    assert kinds == ["steady_sliding", "stick_slip"]
    # steady sliding x = mu(Vb) g / w^2; every stick ends at (mu_s g - 2 beta w Vb) / w^2
    mu = MU_K + (MU_S - MU_K) * math.exp(-2.5)
    assert out["attractors"][0]["state"] == pytest.approx([mu * G, 0.0], abs=1e-12)
    assert out["attractors"][1]["state"] == pytest.approx([MU_S * G - 2 * BETA * 2.5, 2.5])
    assert sum(a["share"] for a in out["attractors"]) == pytest.approx(1.0)
    found = _json("responses", *model)
    assert [a["kind"] for a in found["attractors"]] == kinds
    assert all(a["stable"] for a in found["attractors"])


def test_coexistence_and_basin_stability_of_belt_1dof():
    model = ["--model", "belt_1dof", "--friction", "stribeck"]
    # below the Hopf point v_s ln(g (mu_s - mu_k) / (2 beta w v_s)) = 1.9957 only the
    # stick-slip cycle; at 2.5 steady sliding too; at 3.5 only steady sliding from these
    # starts
    out = _json(
        "coexistence", *model, "--param", "Vb", "--from", "1.5", "--to", "3.5", "--step", "1"
    )
    assert out["model"] == "belt_1dof" and out["ranges"] == [[2.5, 2.5]]
    assert [len(p["attractors"]) for p in out["points"]] == [1, 2, 1]
    out = _json(
        "basin-stability", *model, "--param", "Vb", "--from", "1.5", "--to", "2.5",
        "--points", "2", "--x-from", "1.5", "--x-to", "3.5", "--y-from", "-3", "--y-to",
        "0.5", "--samples", "5",
    )  # fmt: skip
    first, last = out["points"]
    assert [a["kind"] for a in first["attractors"]] == ["stick_slip"]
    assert first["attractors"][0]["fraction"] == 1.0
    for a in last["attractors"]:
        p = a["fraction"]
        assert a["error"] == pytest.approx(math.sqrt(p * (1 - p) / 5))
    assert sum(a["fraction"] for a in last["attractors"]) + last["unresolved"] == pytest.approx(1)


def test_basin_stability_in_python_is_the_commands_for_another_model():
    """beltmdsm.basin.basin_stability of another model: the command's numbers (one
    path: the generic runtime's), its own refusals naming what it lacks."""
    import beltmdsm
    from beltmdsm.basin.basin_stability import basin_stability
    from beltmdsm.errors import Unsupported

    m = beltmdsm.Model(model="belt_1dof", friction="stribeck", Vb=2.5)
    box = {"x": (1.5, 3.5), "x_dot": (-3.0, 0.5)}
    r = basin_stability(m, box, samples=5, seed=3)
    out = _json(
        "basin-stability", "--model", "belt_1dof", "--friction", "stribeck", "--param",
        "Vb", "--from", "2.5", "--to", "3.0", "--points", "2", "--x-from", "1.5",
        "--x-to", "3.5", "--y-from", "-3", "--y-to", "0.5", "--samples", "5", "--seed", "3",
    )  # fmt: skip
    assert r.as_dict()["attractors"] == out["points"][0]["attractors"]
    assert r.samples == 5 and (r.x, r.y) == ("x", "x_dot")
    with pytest.raises(ValueError, match="region must map two of model 'belt_1dof'"):
        basin_stability(m, {"x": (1.5, 3.5)}, samples=5)
    with pytest.raises(Unsupported, match="landscape="):
        basin_stability(m, box, samples=5, landscape=object())
    assert m.capabilities["basin_stability"] == (True, "")


def test_the_papers_json_names_its_model_too():
    out = _json("simulate", "--t-end", "5", "--t-discard", "1")
    assert out["model"] == "paper" and "friction" in out and "params" in out
