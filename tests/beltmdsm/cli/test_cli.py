"""The one command line (beltmdsm/cli/, the derive commands of derive/commands.py): flags
checked, one-line errors, the shared parents, the executor factory, the console script,
predict's edge cases."""

import concurrent.futures as cf
import json
import os
import shutil
import subprocess
import sys
from argparse import Namespace
from pathlib import Path

import pytest
from inprocess import once

from beltmdsm.cli import flags, main, tree
from beltmdsm.cli.parser import Parser, UsageError
from beltmdsm.model import OPTIONS, Model
from beltmdsm.prediction import prediction, scan

ROOT = Path(__file__).resolve().parents[3]


def _fails(capsys, argv, *names):
    """``argv`` exits 2 with one line on stderr naming each of ``names``; nothing on stdout."""
    assert main(argv) == 2
    out, err = capsys.readouterr()
    assert out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert "error:" in lines[0] and "Traceback" not in err
    for name in names:
        assert name in lines[0], lines[0]
    return lines[0]


@pytest.mark.parametrize(
    "argv, names",
    [
        (["simulate", "--mu_s", "-1"], ["--mu_s", ">= 0"]),
        (["simulate", "--mu-s", "nan"], ["--mu_s/--mu-s", "finite"]),
        (["simulate", "--Vb", "inf"], ["--Vb", "finite"]),
        (["simulate", "--omega1", "0"], ["--omega1", "> 0"]),
        (["simulate", "--beta2", "-0.1"], ["--beta2", ">= 0"]),
        (["simulate", "--Omega", "-4"], ["--Omega", ">= 0"]),
        (["simulate", "--phase-t", "x"], ["--phase_t", "must be a number"]),
        (["simulate", "--t-end", "0"], ["--t-end", "> 0"]),
        (["simulate", "--t-end", "-5"], ["--t-end", "> 0"]),
        (["simulate", "--dt", "0"], ["--dt", "> 0"]),
        (["simulate", "--rtol", "0"], ["--rtol", "> 0"]),
        (["simulate", "--atol=-1e-9"], ["--atol", "> 0"]),
        (["simulate", "--t-discard", "-1"], ["--t-discard", ">= 0"]),
        (["simulate", "--t-end", "100", "--t-discard", "99.8"], ["--t-discard", "steady window"]),
        (["simulate", "--t-end", "1e9"], ["--t-end", "MAX_SAMPLES"]),
        (["simulate", "--method", "Euler"], ["--method", "invalid choice"]),
        (["simulate", "--contact", "coulomb"], ["--contact", "invalid choice"]),
        (["simulate", "--solver", "rk4"], ["--solver", "invalid choice"]),
        (["simulate", "--bogus", "1"], ["unrecognized arguments: --bogus"]),
        (
            ["simulate", "--save", "/nonexistent/run.npz"],
            ["--save", "/nonexistent", "does not exist"],
        ),
        (["frobnicate"], ["COMMAND", "frobnicate"]),
        (["--check", "simulate"], ["--check"]),
        (
            ["sweep", "--param", "Vb", "--from", "1", "--to", "2", "--step", "1e-15"],
            ["--step", "MAX_POINTS"],
        ),
        (
            ["sweep", "--param", "Vb", "--from", "2", "--to", "1", "--step", "0.5"],
            ["--to", "--from"],
        ),
        (["sweep", "--param", "Vb", "--from", "1", "--to", "2", "--step", "0"], ["--step", "> 0"]),
        (["sweep", "--param", "Vb", "--from", "1", "--to", "2", "--step", "-1"], ["--step", "> 0"]),
        (
            ["sweep", "--param", "Vb", "--from", "nan", "--to", "2", "--step", "1"],
            ["--from", "finite"],
        ),
        (["sweep", "--param", "Vb", "--from", "1", "--to", "2"], ["--from, --to and --step"]),
        (["sweep", "--param", "Vhat", "--values", "1"], ["--param", "invalid choice"]),
        (["sweep", "--param", "Vb", "--values", "1", "inf"], ["--values", "finite"]),
        (["sweep", "--param", "Vb", "--values", "-1"], ["'Vb'", ">= 0"]),  # found deeper
        (["sweep", "--param", "Vb", "--values", "1", "--Vb", "3"], ["--Vb", "walked"]),
        (
            ["sweep", "--param", "Vb", "--values", "5", "--from", "1", "--to", "3", "--step", "1"],
            ["--values", "--from, --to, --step", "not both"],
        ),
        (
            ["floquet-band", "--param", "Vb", "--from", "1", "--to", "3", "--Vb", "3"],
            ["--Vb", "walked"],
        ),
        (
            ["floquet-band", "--param", "Vb", "--from", "-1", "--to", "9"],
            ["[-1, 9]", "Vb must be >= 0"],
        ),
        (
            ["floquet-band", "--param", "omega1", "--from", "0", "--to", "9"],
            ["omega1 must be > 0"],
        ),
        (["sweep", "--param", "Vb", "--values", "1", "--jobs", "0"], ["--jobs", ">= 1"]),
        (
            ["sweep", "--param", "Vb", "--values", "1", "--out", "/nonexistent/x.csv"],
            ["--out", "/nonexistent", "does not exist"],
        ),
        (["predict", "--mu_s", "-1"], ["--mu_s", ">= 0"]),
        (["predict", "--vb-points", "0"], ["--vb-points", ">= 2"]),
        (["predict", "--vb-points", "1.5"], ["--vb-points", "integer"]),
        (["predict", "--vb-max", "0"], ["--vb-max", "> 0"]),
        (["predict", "--vb-max", "-3"], ["--vb-max", "> 0"]),
        (["predict", "--Vb", "3"], ["--Vb"]),  # predict scans Vb itself
        (["validate", "--jobs", "0"], ["--jobs", ">= 1"]),
        (["validate", "--out", "/nonexistent/V.md"], ["--out", "does not exist"]),
    ],
)
def test_a_bad_flag_is_one_line_naming_it_and_exit_2(capsys, argv, names):
    _fails(capsys, argv, *names)


def test_the_sweep_checks_its_output_before_it_computes(capsys, monkeypatch, tmp_path):
    from beltmdsm.batch import sweep

    def never(*args, **kwargs):
        raise AssertionError("computed before checking --out")

    monkeypatch.setattr(sweep, "sweep", never)
    _fails(
        capsys,
        [
            "sweep",
            "--param",
            "Vb",
            "--from",
            "1",
            "--to",
            "2",
            "--step",
            "1",
            "--out",
            str(tmp_path / "missing" / "x.csv"),
        ],
        "--out",
        "does not exist",
    )
    _fails(
        capsys,
        ["sweep", "--param", "Vb", "--values", "1", "--out", str(tmp_path)],
        "--out",
        "is a folder",
    )


def test_a_file_where_the_cache_folder_should_be_is_refused(capsys, tmp_path):
    (tmp_path / "f").write_text("")
    _fails(
        capsys,
        ["sweep", "--param", "Vb", "--values", "1", "--cache-dir", str(tmp_path / "f")],
        "--cache-dir",
        "not a folder",
    )


def test_both_spellings_of_a_parameter_flag_work(capsys):
    for flag in ("--mu_s", "--mu-s"):
        assert main(["simulate", flag, "0.3", "--Vb", "12", "--t-end", "30", "--json"]) == 0
        assert json.loads(capsys.readouterr().out)["params"]["mu_s"] == 0.3


def test_help_returns_0(capsys):
    assert main(["sweep", "--help"]) == 0
    out = capsys.readouterr().out
    assert "--scheduler" in out and "--mu_s" in out and "--mu-s" in out


def test_a_real_subprocess_prints_one_line_and_no_traceback():
    for entry, argv, flag in (
        ("derive", ["simulate", "--mu_s", "-1"], "--mu_s"),
        ("beltmdsm", ["predict", "--vb-points", "0"], "--vb-points"),
        (
            "derive",
            ["sweep", "--param", "Vb", "--from", "0", "--to", "1", "--step", "1e-15"],
            "--step",
        ),
    ):
        r = subprocess.run(
            [sys.executable, "-m", entry, *argv], capture_output=True, text=True, cwd=ROOT
        )
        assert r.returncode == 2
        assert r.stdout == "" and "Traceback" not in r.stderr
        assert len(r.stderr.strip().splitlines()) == 1 and flag in r.stderr


def test_the_cli_path_of_a_runtime_command_does_not_import_sympy():
    code = (
        "import sys\nfrom beltmdsm.cli import main\n"
        "rc = main(['simulate', '--Vb', '12', '--t-end', '30', '--json'])\n"
        "sys.exit(3 if any(m == 'sympy' or m.startswith('sympy.') for m in sys.modules) "
        "else rc)"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT)
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["params"]["Vb"] == 12.0


def test_regeneration_works_when_the_runtime_cannot_be_loaded(tmp_path):
    """The runtime imports generated/, which `python -m derive` exists to rewrite: a
    broken generated module fails the commands that need it, in one line, and never the
    derive commands."""
    for part in ("derive", "generated", "beltmdsm"):
        shutil.copytree(ROOT / part, tmp_path / part, ignore=shutil.ignore_patterns("__pycache__"))
    env = {**os.environ, "PYTHONDONTWRITEBYTECODE": "1"}

    def run(*argv):
        return subprocess.run(
            [sys.executable, "-m", "derive", *argv],
            capture_output=True,
            text=True,
            cwd=tmp_path,
            env=env,
        )

    # a broken module that the flags do not need: --help lists every command, the run
    # says in one line what cannot be loaded
    (tmp_path / "generated" / "dynamics.py").write_text("def (:\n")
    r = run("--help")
    assert r.returncode == 0 and "--check" in r.stdout and "simulate" in r.stdout
    r = run("simulate")
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert "runtime commands cannot be loaded: SyntaxError" in r.stderr
    assert "generated/dynamics.py, line 1" in r.stderr and len(r.stderr.splitlines()) == 1
    # a broken parameter table: the runtime commands are gone from --help, with the reason
    (tmp_path / "generated" / "parameters.py").write_text("def (:\n")
    r = run("--help")
    assert r.returncode == 0 and "--check" in r.stdout
    assert "runtime commands cannot be loaded: SyntaxError" in r.stdout
    r = run("simulate")
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert "cannot be loaded" in r.stderr


# ---------------------------------------------------------------- the console script


def test_the_console_script_is_declared_and_resolves_to_main(monkeypatch):
    tomllib = pytest.importorskip("tomllib")
    with open(ROOT / "pyproject.toml", "rb") as fh:
        scripts = tomllib.load(fh)["project"]["scripts"]
    module, _, name = scripts["beltmdsm"].partition(":")
    import gc
    import importlib

    import beltmdsm.__main__

    # `main` as a program (beltmdsm/__main__.py: the heap frozen before the exit)
    target = getattr(importlib.import_module(module), name)
    assert target is beltmdsm.__main__.program
    # the script wrapper passes the return value to sys.exit: it must be the status
    monkeypatch.setattr(sys, "argv", ["beltmdsm", "predict", "--vb-points", "0"])
    try:
        assert target() == 2
    finally:
        gc.unfreeze()


def test_the_program_name_follows_the_console_script(monkeypatch):
    monkeypatch.setattr(sys, "argv", ["/usr/bin/beltmdsm"])
    assert tree.build_parser(runtime=False).prog == "beltmdsm"
    monkeypatch.setattr(sys, "argv", ["/x/beltmdsm/__main__.py"])
    assert tree.build_parser(runtime=False).prog == "python -m beltmdsm"


def test_python_m_derive_runs_python_m_beltmdsm_and_says_so():
    """The old spelling, from the checkout's root: the same tree, its usage naming the
    new spelling; of derive/ only the package itself is imported by its old name (to
    find its __main__), no module of it and nothing of generated/."""
    r = subprocess.run(
        [sys.executable, "-X", "importtime", "-m", "derive", "--help"],
        capture_output=True, text=True, cwd=ROOT,
    )  # fmt: skip
    assert r.returncode == 0, r.stderr
    usage = "usage: python -m beltmdsm [-h] [--regenerate] [--check] [--out DIR]"
    assert r.stdout.startswith(usage)
    assert "simulate" in r.stdout and "check-paper" in r.stdout
    imported = {line.rsplit("|", 1)[1].strip() for line in r.stderr.splitlines() if "|" in line}
    assert "beltmdsm.derive.commands" in imported and "beltmdsm.generated" in imported
    old = {m for m in imported if m.split(".")[0] in ("derive", "generated")}
    assert old == {"derive"}, old


# ---------------------------------------------------------------- shared parents


def _subparser(parser, name):
    action = next(a for a in parser._actions if a.dest == "command")
    return action.choices[name]


def _parser():
    return tree.build_parser()


def test_every_runtime_command_takes_the_model_flags_it_should():
    parser = _parser()
    params = [p["name"] for p in flags._MODEL_PARAMS]
    for command in ("simulate", "sweep", "predict"):
        taken = {s for a in _subparser(parser, command)._actions for s in a.option_strings}
        expected = {f"--{n}" for n in params if not (command == "predict" and n == "Vb")}
        assert expected <= taken and "--contact" in taken and "--mu-s" in taken
    assert "--Vb" not in {
        s for a in _subparser(parser, "predict")._actions for s in a.option_strings
    }
    for command in ("sweep", "validate"):
        taken = {s for a in _subparser(parser, command)._actions for s in a.option_strings}
        assert {"--jobs", "--scheduler", "--no-cache", "--cache-dir"} <= taken


def test_every_model_option_is_a_flag_of_every_command_but_validate():
    parser = _parser()
    extra = {
        "sweep": ["--param", "Vb"],
        "floquet-band": ["--param", "Vb", "--from", "1", "--to", "2"],
    }
    for command in ("simulate", "sweep", "predict", "floquet", "floquet-band", "validate"):
        for option, choices in OPTIONS.items():
            if command == "validate" and option != "tension":
                continue
            args = parser.parse_args([command, f"--{option}", choices[-1]] + extra.get(command, []))
            assert getattr(args, option) == choices[-1]
            args = parser.parse_args([command] + extra.get(command, []))
            assert getattr(args, option) == choices[0]
            with pytest.raises(UsageError, match=f"--{option}"):
                parser.parse_args([command, f"--{option}", "nonsense"])


# ---------------------------------------------------------------- the executor factory


def _executor_args(jobs=None, scheduler=None):
    return Namespace(jobs=jobs, scheduler=scheduler, parser=Parser(prog="test"))


def test_executor_factory_serial_pool_default():
    with flags.executor_from(_executor_args(jobs=1)) as ex:
        assert ex == "serial"
    with flags.executor_from(_executor_args()) as ex:
        assert ex is None
    with flags.executor_from(_executor_args(jobs=2)) as ex:
        assert isinstance(ex, cf.ProcessPoolExecutor)
        assert ex.submit(abs, -3).result() == 3
    with pytest.raises(RuntimeError):  # closed afterwards
        ex.submit(abs, -3)


def test_executor_factory_dask_client_is_closed_and_failures_name_the_flag(monkeypatch):
    distributed = pytest.importorskip("distributed")
    events = []

    class FakeExecutor:
        def shutdown(self):
            events.append("shutdown")

    class FakeClient:
        def __init__(self, address, timeout):
            if address.endswith(":9"):
                raise OSError(f"Timed out trying to connect to {address}")
            events.append(address)

        def get_executor(self):
            return FakeExecutor()

        def close(self):
            events.append("close")

    monkeypatch.setattr(distributed, "Client", FakeClient)
    with flags.executor_from(_executor_args(jobs=4, scheduler="tcp://h:8786")) as ex:
        assert isinstance(ex, FakeExecutor)
    assert events == ["tcp://h:8786", "shutdown", "close"]
    with pytest.raises(UsageError, match="--scheduler: cannot connect"):
        with flags.executor_from(_executor_args(scheduler="tcp://127.0.0.1:9")):
            pass


# ---------------------------------------------------------------- predict


def test_predict_at_resonance_of_the_tangential_oscillator(capsys):
    """Omega = omega1 = 1: the harmonic balance once stepped to V < 0 near Vb = 0."""
    assert main(["predict", "--Omega", "1", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["consistent_mdsm"] == [] and out["reasons"] == {}
    # the linear amplitude at resonance: alpha Omega^3 / (2 beta1 omega1 Omega)
    assert out["paper_tangential_vhat"][0][1] == pytest.approx(2.0 / 0.2)


def test_predict_without_excitation_says_so(capsys, monkeypatch):
    once(monkeypatch, prediction, "predict")  # the text and the JSON: one computation
    assert main(["predict", "--alpha", "0"]) == 0
    text = capsys.readouterr().out
    assert "consistent_mdsm: unstable Vb in none; no fast tangential motion" in text
    assert "no prediction for paper_tangential_vhat: V_hat = 0" in text
    assert main(["predict", "--alpha", "0", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["consistent_mdsm"] == [] and out["paper_coupled_vhat"] is None
    assert out["reasons"]["consistent_mdsm"] == prediction.NO_EXCITATION


def test_predict_with_two_excitation_frequencies_keeps_the_closed_forms(capsys, monkeypatch):
    once(monkeypatch, prediction, "predict")  # the text and the JSON: one computation
    assert main(["predict", "--Omega_t", "6", "--Omega_n", "4"]) == 0
    text = capsys.readouterr().out
    assert (
        "no prediction for consistent_mdsm: the harmonic balance needs one excitation "
        "frequency" in text
    )
    assert "paper_tangential_vhat: unstable Vb in [" in text
    assert main(["predict", "--Omega_t", "6", "--Omega_n", "4", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["consistent_mdsm"] is None and "Omega_t = 6.0" in out["reasons"]["consistent_mdsm"]
    assert len(out["paper_coupled_vhat"]) == 1


def test_predict_reports_a_harmonic_balance_that_does_not_converge(capsys, monkeypatch):
    def diverge(model, guess=None):
        raise RuntimeError(f"harmonic balance did not converge at Vb = {model['Vb']}")

    monkeypatch.setattr(scan, "fast_motion", diverge)
    assert main(["predict"]) == 0
    assert (
        "no prediction for consistent_mdsm: harmonic balance did not converge"
        in capsys.readouterr().out
    )


def test_predict_clipped_keeps_the_closed_forms_and_refuses_the_harmonic_balance(
    capsys, monkeypatch
):
    once(monkeypatch, prediction, "predict")  # the text and the JSON: one computation
    assert main(["predict", "--json"]) == 0
    allowed = json.loads(capsys.readouterr().out)
    assert main(["predict", "--tension", "clipped", "--json"]) == 0
    clipped = json.loads(capsys.readouterr().out)
    assert allowed["tension"] == "allowed" and clipped["tension"] == "clipped"
    # the linearisation at the equilibrium (force g > 0) does not see the law
    for key in ("paper_tangential_vhat", "paper_coupled_vhat"):
        assert clipped[key] == allowed[key]
        assert clipped["reasons"][key] == prediction.CLIPPED_PAPER
    # the base set's fast normal force g + N1 sin has N1 = 27.2 > g: the clip cuts it
    assert allowed["consistent_mdsm"] and clipped["consistent_mdsm"] is None
    assert "non-harmonic" in clipped["reasons"]["consistent_mdsm"]
    assert "N1 = 27.17 >= g = 9.81" in clipped["reasons"]["consistent_mdsm"]
    assert main(["predict", "--tension", "clipped"]) == 0
    assert (
        "no prediction for consistent_mdsm: tension='clipped': the harmonic balance"
        in capsys.readouterr().out
    )


def test_predict_clipped_where_the_clip_does_not_act_keeps_the_mdsm_with_a_note():
    # alpha = 0.3: N1 = 4.08 < g, so the linear fast normal force never reaches zero
    allowed = prediction.predict(Model(alpha=0.3))
    clipped = prediction.predict(Model(alpha=0.3, tension="clipped"))
    assert clipped.consistent_mdsm == allowed.consistent_mdsm
    assert "the clip does not act on it" in clipped.reasons["consistent_mdsm"]
    with pytest.raises(ValueError, match="tension must be one of"):
        prediction.predict(Model(tension="pulling"))


def test_vb_points_sets_the_default_grid_too():
    _, table = scan.unstable_intervals(points=50)
    assert table["Vb"].size == 50
    with pytest.raises(ValueError, match="points must be an integer >= 2"):
        prediction.predict(points=1)
    with pytest.raises(ValueError, match="vb must be a 1-D grid of at least 2"):
        prediction.predict(vb=[3.0])
    with pytest.raises(ValueError, match="finite belt speeds >= 0"):
        scan.unstable_intervals(vb=[-1.0, 2.0])


def test_regeneration_and_check_paper_do_not_load_the_runtime(monkeypatch):
    def refuse(*args, **kwargs):
        raise AssertionError("the runtime was loaded")

    assert not tree._needs_runtime([]) and not tree._needs_runtime(["--check"])
    assert not tree._needs_runtime(["check-paper"])
    assert not tree._needs_runtime(["--out", "d"]) and not tree._needs_runtime(["--out=d"])
    assert tree._needs_runtime(["--help"]) and tree._needs_runtime(["simulate"])
    monkeypatch.setattr(tree.derive, "generate", lambda args: 0)
    monkeypatch.setattr(tree, "add_commands", refuse)
    assert tree.main(["--check"]) == 0


# ---------------------------------------------------------------- help (issue 17)


def _actions(parser, command="(top)"):
    """``(command, action)`` for every flag of every command of the tree."""
    import argparse

    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                yield from _actions(sub, name)
        elif action.dest != "help":
            yield command, action


def test_every_flag_of_every_command_has_a_help_text_that_states_its_default():
    import argparse

    parser = _parser()
    walked = list(_actions(parser))
    assert {c for c, _ in walked} >= set(tree.COMMANDS) | {"(top)"}
    for command, action in walked:
        name = f"{command} {'/'.join(action.option_strings) or action.dest}"
        assert action.help and action.help != argparse.SUPPRESS, name
        assert len(action.help) >= 12, name  # a sentence, not "> 0"
        takes_value = action.nargs != 0 and action.option_strings
        if takes_value and action.default not in (None, False):
            assert "default" in action.help, name
    (solver,) = [a for c, a in walked if c == "simulate" and a.dest == "solver"]
    assert "(default: events)" in solver.help and "DOP853" in solver.help
