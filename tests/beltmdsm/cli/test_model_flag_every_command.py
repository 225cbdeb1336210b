"""``--model NAME`` on every command of ``python -m beltmdsm`` (issue 39 item 4).

Every subcommand of the tree (`beltmdsm.cli.tree.build_parser`, so that a new one is
covered without an edit here) takes ``--model`` with the registry's choices; a command
that runs another model names it in its JSON; a command that lacks the analysis for a
model refuses it in one line on stderr, naming the command, the model and what it
lacks (the model's ``ABSENT`` piece or `beltmdsm.model.LACKS` and how to get it), with a
non-zero exit status. The acceptance and each command's first refusal run through a
real process (``python -m beltmdsm``); the runs and the other refusals in the test's
process (tests/inprocess.py), where the kernels load once.
"""

import json
import math
import subprocess
import sys
from pathlib import Path

import pytest
from inprocess import cli

from beltmdsm.cli.tree import build_parser
from beltmdsm.generated.models import MODELS, load
from beltmdsm.model import LACKS

ROOT = Path(__file__).resolve().parents[3]
BOX = ["--x-from", "-0.1", "--x-to", "0.1", "--y-from", "-0.1", "--y-to", "0.1"]
FORCED = ["--alpha_t", "0.5", "--Omega_t", "2"]


def _commands() -> list[str]:
    parser = build_parser()
    (sub,) = [a for a in parser._actions if a.dest == "command"]
    return list(sub.choices)


COMMANDS = _commands()

#: A command and a model it lacks: what its refusal must say (the model's own ABSENT
#: text or beltmdsm.model.LACKS, and what gets the analysis where there is a way).
REFUSED = [
    ("check-paper", "belt_1dof", [], load("belt_1dof").ABSENT["paper_check"]),
    ("validate", "hoffmann", [], load("hoffmann").ABSENT["paper_check"]),
    ("predict", "belt_1dof", [], load("belt_1dof").ABSENT["mdsm"]),
    ("predict", "hoffmann", [], load("hoffmann").ABSENT["mdsm"]),
    (
        "floquet-band",
        "hoffmann",
        ["--param", "Vb", "--from", "1", "--to", "2"],
        LACKS["floquet_band"] + ": the model has no excitation terms",
    ),
    (
        "floquet-band",
        "belt_1dof",
        ["--param", "Vb", "--from", "1", "--to", "2"],
        LACKS["floquet_band"] + ": set an excitation amplitude (--alpha_t, --alpha_n)",
    ),
    (
        "floquet-map",
        "hoffmann",
        [
            "--x",
            "Vb",
            "--x-from",
            "1",
            "--x-to",
            "2",
            "--y",
            "mu_s",
            "--y-from",
            "0.3",
            "--y-to",
            "0.4",
        ],
        LACKS["floquet_map"] + ": the model has no excitation terms",
    ),  # fmt: skip
]

#: Each command that runs another model, with cheap arguments (``--json`` where it has one).
RUNS = {
    "simulate": ("hoffmann", ["--t-end", "1", "--json"]),
    "sweep": ("hoffmann", ["--param", "Vb", "--values", "4", "--t-end", "5", "--json"]),
    "floquet": ("belt_1dof", [*FORCED, "--json"]),
    "floquet-band": (
        "belt_1dof",
        [*FORCED, "--param", "Vb", "--from", "3", "--to", "3.1", "--points", "2", "--json"],
    ),  # fmt: skip
    "floquet-map": (
        "belt_1dof",
        [
            *FORCED[:2],
            "--x",
            "Vb",
            "--x-from",
            "3",
            "--x-to",
            "3.1",
            "--y",
            "Omega_t",
            "--y-from",
            "1.9",
            "--y-to",
            "2",
            "--rows",
            "2",
            "--json",
        ],
    ),  # fmt: skip
    "responses": ("hoffmann", ["--json"]),
    "branch": ("hoffmann", ["--param", "Vb", "--from", "3.9", "--to", "4", "--json"]),
    "coexistence": (
        "belt_1dof",
        [
            *FORCED[:2],
            "--param",
            "Omega_t",
            "--from",
            "1.9",
            "--to",
            "2.0",
            "--step",
            "0.05",
            "--json",
        ],
    ),  # fmt: skip
    "lyapunov": ("hoffmann", ["--t-end", "10", "--json"]),
    "basins": ("hoffmann", [*BOX, "--points", "2", "--json"]),
    "basin-stability": (
        "hoffmann",
        ["--from", "3.9", "--to", "4", "--points", "2", "--samples", "2", *BOX, "--json"],
    ),  # fmt: skip
    "docs": ("hoffmann", []),
}


def _beltmdsm(*argv: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "beltmdsm", *argv],
        capture_output=True, text=True, cwd=ROOT, timeout=120,
    )  # fmt: skip


def test_every_command_is_run_or_refused_here():
    """A command added to the tree joins this file: it runs another model or it is
    refused for one."""
    assert set(COMMANDS) == set(RUNS) | {c for c, _, _, _ in REFUSED}


@pytest.mark.parametrize("command", COMMANDS)
def test_every_command_takes_model(command):
    done = _beltmdsm(command, "--model", "hoffmann", "--help")
    assert done.returncode == 0, done.stderr
    assert "--model" in done.stdout and done.stderr == ""
    assert all(name in done.stdout for name in MODELS) or command == "check-paper"


@pytest.mark.parametrize(
    "command, model, argv, why", REFUSED, ids=[f"{c}-{m}" for c, m, _, _ in REFUSED]
)
def test_a_missing_analysis_is_refused_in_one_line(command, model, argv, why):
    # each command's first case through a process, the others in this one (cheaper)
    first = next(m for c, m, _, _ in REFUSED if c == command) == model
    done = (_beltmdsm if first else cli)(command, "--model", model, *argv)
    assert done.returncode != 0 and done.stdout == ""
    (line,) = done.stderr.strip().splitlines()
    assert f"argument --model: {command} does not run model {model!r}: {why}" in line, line


@pytest.mark.parametrize("command", sorted(RUNS))
def test_a_command_that_runs_another_model_names_it(command):
    model, argv = RUNS[command]
    done = cli(command, "--model", model, *argv)
    assert done.returncode == 0, done.stderr
    if "--json" in argv:
        out = json.loads(done.stdout)
        assert out["model"] == model and "X1" not in done.stdout
    else:
        assert done.stdout


def test_basins_samples_of_another_model_is_beltmdsm_basin_stability():
    """``basins --samples N`` of another model ran nowhere (refused as the paper's flag):
    it is `beltmdsm.basin_stability` of the model, each share with its standard error
    sqrt(p (1 - p) / N) (bSTAB's)."""
    import beltmdsm

    argv = ["--friction", "stribeck", "--Vb", "2.5", "--x-from", "1.5", "--x-to", "3.5"]
    argv += ["--y-from", "-3", "--y-to", "0.5", "--samples", "6", "--seed", "3"]
    done = cli("basins", "--model", "belt_1dof", *argv, "--json")
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)
    m = beltmdsm.Model(model="belt_1dof", friction="stribeck", Vb=2.5)
    r = beltmdsm.basin_stability(m, {"x": (1.5, 3.5), "x_dot": (-3.0, 0.5)}, samples=6, seed=3)
    assert out["model"] == "belt_1dof" and out["attractors"] == r.as_dict()["attractors"]
    assert {a["kind"] for a in out["attractors"]} == {"steady_sliding", "stick_slip"}
    for a in out["attractors"]:
        p = a["fraction"]
        assert a["error"] == pytest.approx(math.sqrt(p * (1 - p) / 6), rel=1e-12)
    assert sum(a["fraction"] for a in out["attractors"]) + out["unresolved"] == pytest.approx(1)


def test_a_swept_excitation_amplitude_excites_the_band_and_the_map():
    """``floquet-band --param alpha_t`` of another model was refused as unforced: the
    flags may not set the swept amplitude, so the model had none. The band walks the
    range, as `beltmdsm.floquet_band` does from a model excited inside it."""
    import beltmdsm

    fixed = ["--Omega_t", "2", "--Vb", "3", "--mu_s", "0.1"]
    done = cli("floquet-band", "--model", "belt_1dof", *fixed, "--param", "alpha_t",
               "--from", "0.4", "--to", "0.5", "--points", "3", "--json")  # fmt: skip
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)
    m = beltmdsm.Model(model="belt_1dof", Vb=3.0, mu_s=0.1, Omega_t=2.0, alpha_t=0.45)
    band = beltmdsm.floquet_band(m, "alpha_t", 0.4, 0.5, points=3)
    assert out["model"] == "belt_1dof" and out["unstable"] == band.unstable == []
    assert [g["max_abs_multiplier"] for g in out["grid"]] == pytest.approx(
        [g.max_abs_multiplier for g in band.grid], rel=1e-12
    )
    # Coulomb friction in pure slip is a constant force: the multipliers are the linear
    # oscillator's, exp(-beta1 omega1 T), T = 2 pi / Omega_t
    assert [g["max_abs_multiplier"] for g in out["grid"]] == pytest.approx(
        [math.exp(-0.1 * math.pi)] * 3, rel=1e-9
    )
