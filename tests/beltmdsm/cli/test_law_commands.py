"""The commands under a friction law that the closed forms do not cover (Stribeck's,
derive/laws.py): the general Floquet path named in their output, the superposition
solver's hand-over named with its reason."""

import json

from inprocess import once

from beltmdsm.cli import main
from beltmdsm.prediction import prediction

STRIBECK = ["--friction", "stribeck", "--mu_k", "0.25", "--v_s", "1"]


def test_floquet_says_the_law_and_the_general_path(capsys):
    assert main(["floquet", *STRIBECK, "--Vb", "3", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["friction"] == "stribeck" and out["engine"] == "general"
    assert out["params"]["mu_k"] == 0.25 and out["params"]["v_s"] == 1.0
    assert len(out["multipliers"]) == 4 and out["stable"] is True
    assert main(["floquet", "--Vb", "3", "--json"]) == 0
    coulomb = json.loads(capsys.readouterr().out)
    assert coulomb["engine"] == "closed_form"
    # not Coulomb's answer under another name
    assert abs(coulomb["max_abs_multiplier"] - out["max_abs_multiplier"]) > 0.01
    assert main(["floquet", *STRIBECK, "--Vb", "3"]) == 0
    text = capsys.readouterr().out
    assert "stribeck friction" in text and "general path" in text


def test_floquet_band_under_stribeck_friction(capsys):
    args = ["floquet-band", *STRIBECK, "--param", "Vb", "--from", "5", "--to", "7.5"]
    assert main([*args, "--points", "6", "--json"]) == 0
    band = json.loads(capsys.readouterr().out)
    assert band["friction"] == "stribeck" and band["engine"] == "general"
    ((lo, hi),) = band["unstable"]
    # Coulomb's band is [4.06, 6.42] (tests/beltmdsm/cli/test_commands.py): lower friction
    # moves it up
    assert 5.5 < lo < 6 and 6.9 < hi < 7.2
    assert [e["kind"] for e in band["edges"]] == ["neimark_sacker", "tangency", "grazing"]


def test_simulate_superposition_hands_stribeck_to_events_and_says_why(capsys):
    args = ["simulate", *STRIBECK, "--Vb", "4", "--solver", "superposition", "--t-end", "60"]
    assert main([*args, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["friction"] == "stribeck" and out["solver"] == "events"
    assert "superposition: friction='stribeck'" in out["message"]
    assert "X1'" in out["message"]


def test_simulate_from_the_periodic_response_under_stribeck_friction(capsys):
    args = ["simulate", *STRIBECK, "--Vb", "3", "--t-end", "200", "--start", "periodic"]
    assert main([*args, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    # stable by Floquet (the general path): the perturbed run settles back on the
    # periodic response, whose two reversals per period continue
    assert out["start"] == "periodic" and out["regime"] == "sliding_with_reversals"


def test_predict_under_stribeck_prints_numeric_paper_intervals(capsys, monkeypatch):
    """Issue 19: predict followed Coulomb's law whatever the model's (the paper's
    intervals of Coulomb's closed form under Stribeck's name). Now the paper's
    analysis, which has no closed form under Stribeck's law (closed_form_average), is
    solved numerically from the pointwise growth rate, each row saying so, and the
    consistent MDSM computes with Stribeck's averages: the band [5.878, 7.083], not
    Coulomb's [4.682, 6.375]. (The text and the JSON of one prediction, computed once.)"""
    once(monkeypatch, prediction, "predict")
    assert main(["predict", *STRIBECK, "--no-progress"]) == 0
    lines = capsys.readouterr().out.strip().splitlines()
    assert len(lines) == 3
    for line, key, interval in zip(
        lines,
        ("paper_tangential_vhat", "paper_coupled_vhat"),
        ("[3.805, 8.521]", "[0.000, 7.118]"),
    ):
        assert line.strip().startswith(f"{key}: unstable Vb in {interval}; numeric (")
        assert "friction='stribeck' has no closed-form fast average" in line
    assert lines[2] == "       consistent_mdsm: unstable Vb in [5.878, 7.083]"
    assert main(["predict", *STRIBECK, "--no-progress", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["friction"] == "stribeck" and out["contact"] == "hertz_damp"
    ((lo, hi),) = out["paper_tangential_vhat"]
    assert abs(lo - 3.804882953858) < 1e-9 and abs(hi - 8.521258261835) < 1e-9
    assert "closed_form_average" in out["reasons"]["paper_coupled_vhat"]
    ((lo, hi),) = out["consistent_mdsm"]
    assert abs(lo - 5.878018659582) < 1e-8 and abs(hi - 7.082839963373) < 1e-8
    assert "consistent_mdsm" not in out["reasons"]


def test_predict_stribeck_with_mu_k_equal_to_mu_s_is_coulombs_consistent_mdsm(capsys):
    assert main(["predict", "--vb-points", "40", "--json"]) == 0
    coulomb = json.loads(capsys.readouterr().out)
    argv = ["predict", "--friction", "stribeck", "--mu_k", "0.4", "--vb-points", "40"]
    assert main([*argv, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    ((lo, hi),) = out["consistent_mdsm"]
    ((c_lo, c_hi),) = coulomb["consistent_mdsm"]
    assert abs(lo - c_lo) < 1e-12 and abs(hi - c_hi) < 1e-12
    # the paper's analysis has no closed form all the same (its average is a
    # quadrature): the numeric path gives Coulomb's closed-form interval
    ((lo, hi),) = out["paper_coupled_vhat"]
    ((c_lo, c_hi),) = coulomb["paper_coupled_vhat"]
    assert abs(lo - c_lo) < 1e-11 and abs(hi - c_hi) < 1e-11
    assert out["reasons"]["paper_coupled_vhat"].startswith("numeric (")


def test_predict_under_other_contact_laws_takes_their_physics(capsys):
    assert main(["predict", "--contact", "kelvin_voigt", "--json"]) == 0
    kv = json.loads(capsys.readouterr().out)
    assert kv["contact"] == "kelvin_voigt"
    assert abs(kv["paper_coupled_vhat"][0][1] - 8.5714) < 1e-4  # Hertz-Damp's: 6.375
    assert kv["consistent_mdsm"] == []
    assert main(["predict", "--contact", "hunt_crossley", "--n_h", "1.5", "--json"]) == 0
    hc = json.loads(capsys.readouterr().out)
    assert main(["predict", "--json"]) == 0
    hd = json.loads(capsys.readouterr().out)
    for key in ("paper_tangential_vhat", "paper_coupled_vhat", "consistent_mdsm"):
        for (a, b), (c, d) in zip(hc[key], hd[key]):
            assert abs(a - c) < 1e-9 and abs(b - d) < 1e-9
