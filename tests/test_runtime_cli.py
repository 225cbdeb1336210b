"""``python -m derive simulate|sweep`` (dispatched to runtime.cli.main)."""
import json
import subprocess
import sys

from runtime.cli import main


def test_simulate_json_has_the_documented_keys(capsys):
    assert main(["simulate", "--Vb", "4", "--t-end", "100", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    for key in ("regime", "peak_omega1", "peak_Omega", "energy_residual", "n_switches", "wall_s"):
        assert key in out
    assert out["params"]["Vb"] == 4.0
    assert out["energy_residual"] < 1e-8


def test_simulate_readable_summary(capsys):
    assert main(["simulate", "--Vb", "12", "--beta1", "0.2", "--t-end", "80", "--modulation"]) == 0
    text = capsys.readouterr().out
    assert "regime:" in text and "energy balance" in text and "mu_eff" in text


def test_sweep_prints_table_and_validation_line(capsys, tmp_path):
    csv = tmp_path / "s.csv"
    assert main(["sweep", "--param", "Vb", "--from", "4", "--to", "12", "--step", "8",
                 "--t-end", "60", "--jobs", "1", "--no-cache", "--no-progress",
                 "--out", str(csv)]) == 0
    text = capsys.readouterr().out
    assert "omega1 peak" in text and "paper:" in text
    assert csv.read_text().startswith("Vb,regime,")


def test_bad_parameter_gives_a_clear_error(capsys):
    assert main(["simulate", "--Vb", "-3"]) == 2
    assert "Vb" in capsys.readouterr().err


def test_module_entry_point_dispatches_simulate():
    r = subprocess.run([sys.executable, "-m", "derive", "simulate", "--Vb", "12", "--t-end", "50",
                        "--json"], capture_output=True, text=True, check=True)
    assert json.loads(r.stdout)["regime"] == "continuous_sliding"
