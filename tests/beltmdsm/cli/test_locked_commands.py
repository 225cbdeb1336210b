"""``python -m beltmdsm responses|branch|coexistence|floquet-map`` and ``--periods``."""

import json

import pytest
from inprocess import once

from beltmdsm.cli import flags, main
from beltmdsm.periodic.locked import LOCK_LIMIT


def test_floquet_of_four_periods_keeps_the_keys_of_floquet(capsys, monkeypatch):
    from beltmdsm.periodic import floquet as floquet_module

    once(monkeypatch, floquet_module, "floquet")  # the text and the JSON: one computation
    assert main(["floquet", "--Vb", "5", "--json"]) == 0
    one = json.loads(capsys.readouterr().out)
    assert main(["floquet", "--Vb", "5", "--periods", "4", "--json"]) == 0
    four = json.loads(capsys.readouterr().out)
    assert set(one) == set(four)
    assert (one["periods"], four["periods"]) == (1, 4)
    assert four["stable"] is True and one["stable"] is False
    assert four["period"] == pytest.approx(4 * one["period"])
    assert main(["floquet", "--Vb", "5", "--periods", "4"]) == 0
    assert "per 4 periods" in capsys.readouterr().out


def test_responses_json_lists_every_response_with_the_contract_keys(capsys):
    assert main(["responses", "--Vb", "5", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    keys = {
        "periods",
        "stable",
        "max_abs_multiplier",
        "multipliers",
        "n_reversals",
        "n_sticks",
        "amplitude",
    }
    assert [r["periods"] for r in out["responses"]] == [1, 4]
    assert all(keys <= set(r) for r in out["responses"])
    assert [r["stable"] for r in out["responses"]] == [False, True]
    # below the band the run from rest locks only after 59 periods: classified (issue 31)
    assert main(["responses", "--Vb", "3.5", "--ladder", "0"]) == 0
    text = capsys.readouterr().out
    assert "59T" in text and "run from rest (classified)" in text


def test_branch_text_and_json(capsys, monkeypatch):
    from beltmdsm import branches as branch_module

    once(monkeypatch, branch_module, "branch")  # the text and the JSON: one computation
    args = ["branch", "--Vb", "5", "--periods", "4", "--param", "Vb", "--from", "2", "--to", "9"]
    assert main(args + ["--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert [s["kind"] for s in out["special_points"]] == ["grazing", "fold", "tangency"]
    assert out["stable_ranges"] == [pytest.approx([3.869919, 7.673801], abs=1e-5)]
    assert main(args) == 0
    text = capsys.readouterr().out
    assert "fold at Vb = 7.6738" in text and "stable for Vb in [3.86992, 7.67380]" in text


def test_coexistence_json_contract(capsys):
    assert main(["coexistence", "--param", "Vb", "--from", "6", "--to", "8", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    (c,) = out["coexistence"]
    assert set(c) == {"range", "responses", "lower", "upper"}
    assert c["range"] == pytest.approx([6.415415, 7.673801], abs=1e-5)
    assert (c["lower"], c["upper"]) == ("grazing", "fold")
    assert "4T" in c["responses"] and len(c["responses"]) == 2
    assert main(["coexistence", "--param", "Vb", "--from", "6", "--to", "8"]) == 0
    assert "(grazing to fold)" in capsys.readouterr().out


def test_floquet_map_json_and_png(capsys, tmp_path):
    png = tmp_path / "map.png"
    args = ["floquet-map", "--x", "Vb", "--x-from", "0.5", "--x-to", "12", "--y", "beta1"]
    args += ["--y-from", "0.05", "--y-to", "0.2", "--rows", "3"]
    assert main(args + ["--json", "--png", str(png)]) == 0
    out = json.loads(capsys.readouterr().out)
    assert {c["kind"] for c in out["curves"]} == {"neimark_sacker", "tangency", "grazing"}
    assert len(out["unstable"]) == len(out["linear"]) == 3
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 1000


@pytest.mark.parametrize(
    "args",
    [
        ["floquet", "--Vb", "5", "--periods", "0"],
        ["branch", "--Vb", "5", "--param", "Vb", "--from", "6", "--to", "9"],
        ["branch", "--param", "Vb", "--from", "2", "--to", "9"],
        ["branch", "--param", "beta1", "--from", "0.1", "--to", "0.05"],
        ["coexistence", "--param", "Vb", "--from", "5", "--to", "5"],
        ["coexistence", "--Vb", "5", "--param", "Vb", "--from", "4", "--to", "6"],
        ["floquet-map", "--x", "Vb", "--x-from", "1", "--x-to", "2", "--y", "Vb"]
        + ["--y-from", "1", "--y-to", "2"],
        ["floquet-map", "--Vb", "3", "--x", "Vb", "--x-from", "1", "--x-to", "2"]
        + ["--y", "beta1", "--y-from", "0.1", "--y-to", "0.2"],
        ["responses", "--limit", "0"],
    ],
)
def test_bad_flags_are_one_line_errors(capsys, args):
    assert main(args) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "error" in err[0]


def test_the_band_of_the_4T_response_ends_at_its_grazing_and_its_fold(capsys):
    args = ["floquet-band", "--param", "Vb", "--from", "3", "--to", "9", "--periods", "4"]
    assert main(args + ["--points", "9", "--json"]) == 0
    band = json.loads(capsys.readouterr().out)
    assert [(e["kind"], round(e["value"], 5)) for e in band["edges"]] == [
        ("grazing", 3.86992),
        ("fold", 7.6738),
    ]
    # past the fold the branch comes back unstable over values where the stable part is:
    # the band keeps the stable part (no degenerate unstable ranges there)
    assert band["unstable"] == [
        [3.0, pytest.approx(3.869919, abs=1e-5)],
        [pytest.approx(7.673801, abs=1e-5), 9.0],
    ]


def test_the_limit_flag_defaults_to_the_analysis_limit():
    assert flags.LOCK_LIMIT == LOCK_LIMIT
