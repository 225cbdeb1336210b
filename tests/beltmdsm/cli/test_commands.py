"""``python -m beltmdsm simulate|sweep`` (dispatched to runtime.cli.main)."""

import json
import math
import subprocess
import sys

from inprocess import once

from beltmdsm.cli import main
from beltmdsm.model import Model


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
    assert (
        main(
            [
                "sweep",
                "--param",
                "Vb",
                "--from",
                "4",
                "--to",
                "12",
                "--step",
                "8",
                "--t-end",
                "60",
                "--jobs",
                "1",
                "--no-cache",
                "--no-progress",
                "--out",
                str(csv),
            ]
        )
        == 0
    )
    text = capsys.readouterr().out
    assert "omega1 peak" in text and "paper:" in text
    assert csv.read_text().startswith("Vb,regime,")


def test_bad_parameter_gives_a_clear_error(capsys):
    assert main(["simulate", "--Vb", "-3"]) == 2
    assert "Vb" in capsys.readouterr().err


def test_module_entry_point_dispatches_simulate():
    r = subprocess.run(
        [sys.executable, "-m", "derive", "simulate", "--Vb", "12", "--t-end", "50", "--json"],
        capture_output=True,
        text=True,
        check=True,
    )
    assert json.loads(r.stdout)["regime"] == "continuous_sliding"


def test_simulate_json_names_the_tension_law(capsys):
    assert main(["simulate", "--Vb", "12", "--t-end", "60", "--tension", "clipped", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["tension"] == "clipped"
    # Eq. (1) pulls at the base set in every excitation cycle: clipped, it separates
    assert out["n_separations"] > 0 and out["time_fraction"]["separated"] > 0
    assert out["min_normal_force"] >= 0


def test_an_unresolved_peak_is_never_called_absent_or_present(capsys):
    # too short a window for the omega1 band
    assert main(["simulate", "--t-end", "30"]) == 0
    text = capsys.readouterr().out
    assert "omega1 peak unresolved (the steady window" in text and "absent" not in text
    # without friction the free transient at omega1 has not decayed by 40 s
    assert main(["simulate", "--mu_s", "0", "--t-end", "40"]) == 0
    text = capsys.readouterr().out
    assert "omega1 peak unresolved (the tangential transient has not decayed" in text
    assert "PRESENT" not in text and "friction-induced" not in text


def test_readable_summary_names_the_modes_in_the_order_of_the_fractions(capsys):
    from beltmdsm.simulation import simulate

    assert main(["simulate", "--Vb", "4", "--t-end", "300"]) == 0
    text = capsys.readouterr().out
    frac = simulate(Model(Vb=4.0), t_end=300.0).summary.time_fraction
    line = next(s for s in text.splitlines() if s.startswith("regime:"))
    assert f"(time in {'/'.join(frac)}: " in line
    assert "/".join(f"{100 * v:.1f}%" for v in frac.values()) in line
    # a resolved peak, the only place for the words on friction-induced vibration
    assert "omega1 peak PRESENT (friction-induced vibration)" in text


def test_sweep_continue_runs_serially_and_says_so(capsys):
    args = [
        "sweep",
        "--param",
        "Vb",
        "--values",
        "14",
        "12",
        "--Omega",
        "6",
        "--t-end",
        "300",
        "--no-cache",
        "--no-progress",
        "--continue",
        "down",
    ]
    assert main(args) == 0
    text = capsys.readouterr().out
    assert "tension allowed; continued down from rest at Vb = 14" in text
    assert main(args + ["--jobs", "2"]) == 2
    assert (
        "argument --continue: a continued sweep runs its points one after another"
        in capsys.readouterr().err
    )
    assert main(args[:-1] + ["sideways"]) == 2
    assert "--continue" in capsys.readouterr().err


def test_floquet_json_keys_and_verdict_match_the_api(capsys):
    from beltmdsm.periodic.floquet import floquet

    assert main(["floquet", "--Vb", "5", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    for key in (
        "multipliers",
        "max_abs_multiplier",
        "growth_rate",
        "frequency",
        "stable",
        "n_reversals",
        "n_sticks",
        "grazing",
        "period",
        "state0",
        "residual",
    ):
        assert key in out
    f = floquet(Model(Vb=5.0))
    assert out["stable"] is False and out["stable"] == f.stable
    assert abs(out["max_abs_multiplier"] - f.max_abs_multiplier) <= 1e-9
    # the growth rate is log|mu|max over the period, by definition
    assert abs(out["growth_rate"] - math.log(out["max_abs_multiplier"]) / out["period"]) < 1e-12


def test_floquet_readable_summary(capsys):
    assert main(["floquet", "--Vb", "4"]) == 0
    text = capsys.readouterr().out
    assert "Floquet multipliers:" in text and "stable" in text and "UNSTABLE" not in text


def test_floquet_band_text_and_json_agree(capsys, monkeypatch):
    from beltmdsm.continuation import band as band_module

    once(monkeypatch, band_module, "floquet_band")  # the text and the JSON: one computation
    args = ["floquet-band", "--param", "Vb", "--from", "3", "--to", "7", "--points", "9"]
    assert main(args) == 0
    text = capsys.readouterr().out
    assert main(args + ["--json"]) == 0
    band = json.loads(capsys.readouterr().out)
    ((lo, hi),) = band["unstable"]
    assert 3 < lo < 5 < hi < 7
    assert f"[{lo:.4f}, {hi:.4f}]" in text
    kinds = {e["kind"]: e["old_kind"] for e in band["edges"]}
    # the bifurcation, and the kind of before for one release
    # (beltmdsm.continuation.edges.OLD_KINDS)
    assert kinds == {"neimark_sacker": "multiplier", "tangency": "existence", "grazing": "grazing"}
    assert all(f"({kind}" in text for kind in kinds)
    # the Neimark-Sacker edge with the frequency of its critical pair
    (ns,) = [e for e in band["edges"] if e["kind"] == "neimark_sacker"]
    assert f"(neimark_sacker at {ns['frequency']:.4g} rad/s; unstable above)" in text


def test_floquet_band_rejects_an_empty_range(capsys):
    assert main(["floquet-band", "--param", "Vb", "--from", "5", "--to", "5"]) == 2
    assert "--to" in capsys.readouterr().err


def test_simulate_from_the_periodic_response(capsys):
    assert main(["simulate", "--Vb", "5", "--t-end", "400", "--start", "periodic", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["start"] == "periodic"
    # Floquet says unstable at Vb = 5: the perturbation grows into the omega1 vibration
    assert out["omega1_peak_present"] is True
    # and at Vb = 3, where it is stable, the perturbation decays
    assert main(["simulate", "--Vb", "3", "--t-end", "400", "--start", "periodic", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["omega1_peak_present"] is False


def test_floquet_band_names_the_sides_of_an_edge_between_two_stable_ranges(capsys, monkeypatch):
    from beltmdsm.continuation import band as band_module

    once(monkeypatch, band_module, "floquet_band")  # the text and the JSON: one computation
    # clipped: the sliding response grazes at a Vb where both sides are stable
    args = ["floquet-band", "--param", "Vb", "--from", "0.5", "--to", "16", "--tension", "clipped"]
    assert main(args + ["--json"]) == 0
    band = json.loads(capsys.readouterr().out)
    assert band["unstable"] == [] and band["edges"]
    assert all(not e["unstable_below"] and not e["unstable_above"] for e in band["edges"])
    assert main(args) == 0
    assert "stable on both sides" in capsys.readouterr().out
