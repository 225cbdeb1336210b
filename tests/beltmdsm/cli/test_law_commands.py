"""The commands under a friction law that the closed forms do not cover (Stribeck's,
derive/laws.py): the general Floquet path named in their output, the superposition
solver's hand-over named with its reason."""

import json

from beltmdsm.cli import main

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
