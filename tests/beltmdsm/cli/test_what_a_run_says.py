"""Issue 17, "What a run says must be true", through the command line, end to end.

Each test reproduces one report of the issue with the command that showed it and
checks what the command says now (`beltmdsm.cli.main` with capsys; a real
subprocess where the exit status and stderr of the program itself matter).
"""

import json
import subprocess
import sys
from pathlib import Path

import pytest
from inprocess import once

from beltmdsm.cli import main
from beltmdsm.prediction import prediction
from beltmdsm.settings import SolverSettings

ROOT = Path(__file__).resolve().parents[3]


def _json(capsys, argv, status=0):
    assert main([*argv, "--json"]) == status
    return json.loads(capsys.readouterr().out)


def _one_line_error(capsys, argv, *names):
    """``argv`` exits 2 with one line on stderr naming each of ``names``; nothing on stdout."""
    assert main(argv) == 2
    out, err = capsys.readouterr()
    assert out == "" and "Traceback" not in err
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    for name in names:
        assert name in lines[0], lines[0]
    return lines[0]


# ---------------------------------------------------------------- 1. no forced peak


def test_simulate_without_excitation_reports_no_vibration(capsys):
    # the report: "omega1 peak PRESENT (friction-induced vibration)", 1.3e-13 against
    # 1.1e-13 at Omega, both rounding noise
    assert main(["simulate", "--alpha", "0", "--t-end", "300"]) == 0
    text = capsys.readouterr().out
    assert "PRESENT" not in text and "friction-induced" not in text
    assert "omega1 peak absent (no forced peak either" in text
    out = _json(capsys, ["simulate", "--alpha", "0", "--t-end", "300"])
    assert out["forced_peak"] is False and out["omega1_peak_present"] is False
    assert out["resolved"] is True
    # both peaks are below the floor of the tolerances, and the floor is far below
    # any vibration worth the name
    assert max(out["peak_omega1"], out["peak_Omega"]) < out["noise_floor"] < 1e-6


def test_sweep_without_excitation_finds_the_peak_nowhere(capsys):
    argv = ["sweep", "--param", "Vb", "--values", "2", "4", "8", "--alpha", "0"]
    argv += ["--t-end", "300", "--jobs", "1", "--no-cache", "--no-progress"]
    assert main(argv) == 0
    text = capsys.readouterr().out
    assert "present at none of the 3 resolved points" in text
    assert "present for Vb in" not in text and "nowhere" not in text
    assert "no forced peak above the noise floor of the tolerances at Vb = 2, 4, 8" in text
    out = _json(capsys, argv)
    assert out["omega1_peak_ranges"] == []
    assert [r["forced_peak"] for r in out["rows"]] == [False] * 3
    assert [r["omega1_peak_present"] for r in out["rows"]] == [False] * 3


def test_a_forced_run_keeps_its_verdict(capsys):
    out = _json(capsys, ["simulate", "--Vb", "4", "--t-end", "300"])
    assert out["forced_peak"] is True and out["omega1_peak_present"] is True
    # the floor of the default tolerances does not touch the 1 % criterion
    assert out["noise_floor"] < 1e-3 * 0.01 * out["peak_Omega"]


# ---------------------------------------------------------------- 2. aliasing


def test_a_sampling_step_that_aliases_is_refused_before_computing(capsys, monkeypatch):
    import beltmdsm.simulation as simulate_module

    def never(*args, **kwargs):
        raise AssertionError("integrated before checking --dt")

    monkeypatch.setattr(simulate_module, "_simulate", never)
    # the report: 2 Omega = 8 rad/s aliased to 2 pi/0.7 - 8 = 0.976 rad/s, "PRESENT"
    line = _one_line_error(capsys, ["simulate", "--Vb", "1", "--dt", "0.7"], "--dt", "alias")
    assert "8 x Omega_t = 32 rad/s" in line and "NYQUIST_MULTIPLE" in line
    _one_line_error(capsys, ["simulate", "--Vb", "1", "--dt", "0.5"], "--dt")
    # a sweep checks every point before it runs any
    _one_line_error(
        capsys,
        ["sweep", "--param", "Omega", "--values", "4", "30", "--no-cache", "--no-progress"],
        "--dt",
        "at Omega = 30",
    )


# ---------------------------------------------------------------- 4. energy residual


def test_a_run_whose_energy_balance_does_not_close_says_so(capsys):
    # the report: rtol 0.1 ended "done" with a residual of 0.265, no warning
    argv = ["simulate", "--rtol", "0.1", "--t-end", "300"]
    assert main(argv) == 0
    text = capsys.readouterr().out
    assert "DOES NOT CLOSE" in text
    assert "warning: the energy balance does not close" in text
    assert "friction-induced" not in text
    out = _json(capsys, argv)
    assert out["energy_ok"] is False and out["energy_residual"] > out["energy_bound"]
    assert len(out["warnings"]) == 1 and "tighten the tolerances" in out["warnings"][0]
    # the default tolerances close it
    out = _json(capsys, ["simulate", "--t-end", "300"])
    assert out["energy_ok"] is True and out["warnings"] == []


def test_the_sweep_marks_points_whose_energy_balance_does_not_close(capsys):
    argv = ["sweep", "--param", "Vb", "--values", "4", "--rtol", "0.1", "--t-end", "300"]
    argv += ["--jobs", "1", "--no-cache", "--no-progress"]
    assert main(argv) == 0
    text = capsys.readouterr().out
    assert "energy_ok" in text.splitlines()[0]
    assert "warning: the energy balance does not close within its bound at Vb = 4" in text
    out = _json(capsys, argv)
    assert out["rows"][0]["energy_ok"] is False


# ---------------------------------------------------------------- 5. resolved


def test_a_slow_decay_towards_the_periodic_response_is_not_called_resolved(capsys):
    # Vb = 4 is stable but next to the Floquet edge 4.058 (|mu| = 0.995 per period):
    # started on the periodic response and moved by 0.5 m, the omega1 component decays
    # at that rate and is still 1 % of the forced peak in the window; the free
    # transient exp(-beta1 omega1 t) alone called it resolved and PRESENT
    argv = ["simulate", "--Vb", "4", "--start", "periodic", "--perturbation", "0.5"]
    out = _json(capsys, argv)
    assert out["resolved"] is False and out["omega1_peak_present"] is None
    assert "Floquet rate |mu| = 0.99" in out["unresolved_reason"]
    assert main(argv) == 0
    text = capsys.readouterr().out
    assert "omega1 peak unresolved (the peak may be a decay towards the periodic" in text
    # from rest the run lands on a self-excited oscillation of constant amplitude,
    # which coexists with the stable periodic response: resolved, and present
    out = _json(capsys, ["simulate", "--Vb", "4"])
    assert out["resolved"] is True and out["omega1_peak_present"] is True


# ---------------------------------------------------------------- 6. no tracebacks


@pytest.mark.parametrize(
    "argv",
    [
        ["floquet", "--mu_s", "1"],
        ["floquet", "--mu_s", "1.5"],
        ["floquet", "--mu_s", "2"],
        ["floquet", "--beta1", "10", "--Vb", "1.1"],
        ["simulate", "--start", "periodic", "--mu_s", "1"],
    ],
)
def test_no_periodic_response_is_one_line(capsys, argv):
    _one_line_error(capsys, argv, "error: no periodic response found")


def test_tolerances_the_integrator_cannot_keep_are_one_line(capsys):
    # refused where they enter (MAX_RTOL, beltmdsm/settings.py), not by the integrator
    # failing somewhere in the run: --rtol 1 stopped the events solver at t = 5.96 s and
    # ran the superposition to "done" once its normal steps were bounded (issue 36)
    for solver in ("events", "superposition"):
        for rtol in ("1", "0.5", "0.100001"):
            argv = ["simulate", "--rtol", rtol, "--solver", solver, "--no-progress"]
            line = _one_line_error(capsys, argv, "argument --rtol:", "MAX_RTOL = 0.1", rtol)
            assert "no significant digit" in line
    with pytest.raises(ValueError, match="rtol must be <= MAX_RTOL = 0.1"):
        SolverSettings(rtol=1.0)
    # the bound itself is a run (one digit), whose energy balance says whether it closes
    assert SolverSettings(rtol=0.1).rtol == 0.1


# ---------------------------------------------------------------- 7. bounded work


def test_a_run_too_large_for_memory_is_refused_before_computing(capsys, monkeypatch):
    import beltmdsm.simulation as simulate_module

    def never(*args, **kwargs):
        raise AssertionError("integrated before checking --t-end")

    monkeypatch.setattr(simulate_module, "_simulate", never)
    # the report: accepted, and 7.1 GB held after 60 s
    line = _one_line_error(capsys, ["simulate", "--t-end", "1e7", "--dt", "1"], "--t-end")
    assert "MAX_RUN_BYTES = 4 GiB" in line and "GiB" in line
    _one_line_error(capsys, ["simulate", "--t-end", "2e5"], "--t-end", "MAX_RUN_BYTES")


# ---------------------------------------------------------------- real processes


def test_a_real_process_refuses_in_one_line_without_a_traceback():
    for argv, flag in (
        (["simulate", "--Vb", "1", "--dt", "0.7"], "--dt"),
        (["simulate", "--t-end", "1e7", "--dt", "1"], "--t-end"),
        # (no progress bar: under load the run may pass the 2 s after which it shows)
        (["simulate", "--rtol", "1", "--no-progress"], "--rtol"),
        (["floquet", "--mu_s", "1"], "no periodic response"),
    ):
        r = subprocess.run(
            [sys.executable, "-m", "beltmdsm", *argv], capture_output=True, text=True, cwd=ROOT
        )
        assert r.returncode == 2, (argv, r.stderr)
        assert r.stdout == "" and "Traceback" not in r.stderr
        assert len(r.stderr.strip().splitlines()) == 1 and flag in r.stderr, r.stderr


def test_a_real_process_says_no_forced_peak():
    r = subprocess.run(
        [sys.executable, "-m", "beltmdsm", "simulate", "--alpha", "0", "--t-end", "300"]
        + ["--no-progress"],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert r.returncode == 0 and r.stderr == ""
    assert "omega1 peak absent (no forced peak either" in r.stdout


# ---------------------------------------------------------------- 3. predict's grid


def test_predict_on_a_coarse_grid_keeps_the_band(capsys):
    # the report: with --vb-points 2 the consistent MDSM found no unstable speed
    ref = _json(capsys, ["predict"])["consistent_mdsm"]
    assert ref[0] == pytest.approx([4.6816, 6.3754], abs=1e-4)
    for points in ("2", "3"):
        out = _json(capsys, ["predict", "--vb-points", points])
        assert out["consistent_mdsm"][0] == pytest.approx(ref[0], abs=1e-8)
        assert len(out["consistent_mdsm"]) == len(ref) == 1
        assert "consistent_mdsm" not in out["reasons"]


def test_predict_without_friction_reports_no_zero_width_band(capsys, monkeypatch):
    # the report: "unstable Vb in [8.521, 8.521]" for both paper readings with --mu_s 0,
    # while beltmdsm.generated.stability.is_stable(mu_s=0, Vb=8.521) is True
    once(monkeypatch, prediction, "predict")  # the text and the JSON: one computation
    assert main(["predict", "--mu_s", "0", "--no-progress"]) == 0
    text = capsys.readouterr().out
    assert "8.521" not in text
    assert " paper_tangential_vhat: unstable Vb in none" in text
    assert "    paper_coupled_vhat: unstable Vb in none" in text
    out = _json(capsys, ["predict", "--mu_s", "0"])
    assert out["paper_tangential_vhat"] == out["paper_coupled_vhat"] == []


def test_predict_refuses_more_points_than_its_cap(capsys):
    _one_line_error(capsys, ["predict", "--vb-points", "100001"], "--vb-points", "<= 100000")
    _one_line_error(capsys, ["predict", "--vb-points", "1e7"], "--vb-points", "integer")


def test_a_real_process_predicts_on_two_points():
    r = subprocess.run(
        [sys.executable, "-m", "beltmdsm", "predict", "--vb-points", "2"],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert r.returncode == 0 and r.stderr == ""
    assert "consistent_mdsm: unstable Vb in [4.682, 6.375]" in r.stdout


# ---------------------------------------------------------------- 6 and 8. floquet-band


def test_floquet_band_refuses_a_tolerance_below_the_rounding(capsys):
    # the report: RecursionError
    argv = ["floquet-band", "--param", "Vb", "--from", "1", "--to", "9", "--tol", "1e-15"]
    line = _one_line_error(capsys, argv, "--tol", "MIN_TOL_ULPS")
    assert "rounding of the range [1, 9]" in line
    argv = ["floquet-band", "--param", "Vb", "--from", "1", "--to", "9", "--points", "100000"]
    _one_line_error(capsys, argv, "--points", "<= 10000")


def test_floquet_band_text_agrees_with_itself(capsys):
    # the report, at --tol 1e-6: "edge at 6.4154 (grazing; stable on both sides)" while
    # "no periodic response in [6.1637, 6.4154]"
    texts = {}
    for tol in ("1e-3", "1e-6"):
        argv = ["floquet-band", "--param", "Vb", "--from", "1", "--to", "9", "--tol", tol]
        assert main(argv) == 0
        texts[tol] = capsys.readouterr().out
    for text in texts.values():
        assert "(grazing; stable on both sides)" not in text
        edges = [line for line in text.splitlines() if "edge at" in line]
        assert [e.split("(")[1] for e in edges] == [
            "neimark_sacker at 1.028 rad/s; unstable above)",
            "tangency; unstable on both sides)",
            "grazing; unstable below)",
        ]
        # the last edge ends both the unstable range and the range without a response
        last = edges[-1].split()[2]
        assert f", {last}] of 1..9" in text and f", {last}]" in text.splitlines()[-1]
    # printed to the digits of the tolerance
    assert "edge at 6.4154147 (grazing; unstable below)" in texts["1e-6"]


# ---------------------------------------------------------------- 7. progress


class _Bars:
    """A stand-in for tqdm.tqdm that records each bar: its keywords and its progress."""

    def __init__(self):
        self.made = []

    def __call__(self, *args, **kwargs):
        bars = self

        class Bar:
            def __init__(self):
                self.kwargs, self.n = kwargs, 0
                bars.made.append(self)

            def update(self, k=1):
                self.n += k

            def close(self):
                self.closed = True

        return Bar()


@pytest.mark.parametrize(
    "argv, desc",
    [
        (["simulate", "--t-end", "300"], "simulate"),
        (["predict"], "predict Vb"),
        (["floquet-band", "--param", "Vb", "--from", "3", "--to", "7"], "floquet-band Vb"),
    ],
)
def test_long_commands_show_progress_on_stderr_unless_told_not_to(capsys, monkeypatch, argv, desc):
    import tqdm

    for flag, shown in (([], True), (["--no-progress"], False)):
        bars = _Bars()
        monkeypatch.setattr(tqdm, "tqdm", bars)
        assert main(argv + flag) == 0
        capsys.readouterr()
        (bar,) = [b for b in bars.made if b.kwargs.get("desc") == desc]
        assert bar.kwargs["disable"] is not shown and bar.closed
        # only once it takes more than 2 s, so that short runs print nothing
        assert bar.kwargs["delay"] == 2 and bar.n > 0
    if desc == "simulate":
        assert bar.kwargs["total"] == 300.0 and bar.n == pytest.approx(300.0)


# ---------------------------------------------------------------- fixed in the move


def _sweep_argv(*extra):
    return ["sweep", "--param", "Vb", "--t-end", "60", "--jobs", "1", "--no-progress", *extra]


def test_a_cache_file_that_is_not_utf8_is_named_recomputed_and_rewritten(capsys, tmp_path):
    cache = tmp_path / "cache"
    argv = _sweep_argv("--values", "4", "12", "--cache-dir", str(cache))
    first = _json(capsys, argv)
    (path, *_) = sorted(cache.glob("*.json"))
    path.write_bytes(bytes(range(128, 256)) * 4)  # no UTF-8 text
    assert main([*argv, "--json"]) == 0
    out, err = capsys.readouterr()
    # one line, naming the file; the sweep goes on and writes its table
    (line,) = err.strip().splitlines()
    assert " sweep: warning: sweep cache file " in line
    assert str(path) in line and "not UTF-8" in line and "recomputed and rewritten" in line
    again = json.loads(out)

    def numbers(rows):
        return [{k: v for k, v in r.items() if k != "wall_s"} for r in rows]

    assert again["n_cached"] == 1 and numbers(again["rows"]) == numbers(first["rows"])
    assert [p["path"] for p in again["cache_problems"]] == [str(path)]
    json.loads(path.read_text())  # rewritten


def test_a_cache_folder_that_cannot_be_written_is_refused_before_computing(capsys, monkeypatch):
    from beltmdsm.batch import sweep as sweep_module

    def never(*args, **kwargs):
        raise AssertionError("computed before checking --cache-dir")

    monkeypatch.setattr(sweep_module, "_cached_run", never)
    assert main(_sweep_argv("--values", "4", "--cache-dir", "/proc/x")) != 0
    out, err = capsys.readouterr()
    assert out == "" and "Traceback" not in err and len(err.strip().splitlines()) == 1
    assert "/proc/x" in err


def test_sweep_values_are_sorted_and_duplicates_run_once(capsys):
    argv = _sweep_argv("--values", "5", "1", "5", "4", "--no-cache")
    assert main(argv) == 0
    text = capsys.readouterr().out
    assert "duplicate values computed once: 5" in text
    lines = text.splitlines()
    rows = lines[1 : next(i for i, line in enumerate(lines) if line.startswith("tension"))]
    assert [float(r.split()[0]) for r in rows] == [1.0, 4.0, 5.0]
    out = _json(capsys, argv)
    assert [r["Vb"] for r in out["rows"]] == [1.0, 4.0, 5.0]
    assert out["dropped_duplicates"] == [5.0] and out["n_points"] == 3


def test_python_and_the_command_line_share_cache_entries(capsys, tmp_path):
    from beltmdsm.batch.sweep import sweep
    from beltmdsm.settings import SolverSettings

    # integers from Python, floats from the command line: one key
    sweep(
        None,
        "Vb",
        [4, 12],
        settings=SolverSettings(t_end=60),
        executor="serial",
        cache_dir=tmp_path,
        progress=False,
    )
    out = _json(capsys, _sweep_argv("--values", "4", "12", "--cache-dir", str(tmp_path)))
    assert out["n_cached"] == 2


def test_sweep_json_holds_what_the_text_says(capsys):
    out = _json(capsys, _sweep_argv("--values", "4", "12", "--no-cache"))
    assert set(out) == {
        "model",  # every command's JSON names its model (issue 39)
        "param",
        "params",
        "contact",
        "friction",
        "tension",
        "settings",
        "continuation",
        "start",
        "rows",
        "omega1_peak_ranges",
        "unresolved",
        "n_points",
        "n_cached",
        "cache_problems",
        "dropped_duplicates",
    }
    assert out["param"] == "Vb" and "Vb" not in out["params"]
    assert out["settings"]["t_end"] == 60.0 and out["n_points"] == len(out["rows"]) == 2
    for key in ("resolved", "omega1_peak_present", "energy_ok", "forced_peak", "noise_floor"):
        assert key in out["rows"][0]


def test_short_runs_print_no_python_warnings():
    # the report: RuntimeWarnings with source lines, once per sweep point
    for argv in (
        ["simulate", "--t-end", "30", "--no-progress"],
        [
            "sweep",
            "--param",
            "Vb",
            "--values",
            "4",
            "12",
            "--t-end",
            "30",
            "--no-cache",
            "--no-progress",
            "--jobs",
            "1",
        ],
    ):
        r = subprocess.run(
            [sys.executable, "-W", "error", "-m", "beltmdsm", *argv],
            capture_output=True,
            text=True,
            cwd=ROOT,
        )
        assert r.returncode == 0 and r.stderr == "", r.stderr
        assert "nan" not in r.stdout and "nowhere" not in r.stdout


def test_validate_writes_into_the_current_folder(capsys, monkeypatch, tmp_path):
    from beltmdsm.cli import text
    from beltmdsm.paper_reports import validation

    monkeypatch.setattr(validation, "validate", lambda *a, **k: {"stub": True})
    monkeypatch.setattr(validation, "render_markdown", lambda results, quick: "# stub\n")
    monkeypatch.setattr(text, "validation", lambda results, out: f"wrote {out}")
    monkeypatch.chdir(tmp_path)
    before = (ROOT / "VALIDATION.md").read_text()
    assert main(["validate", "--quick", "--no-progress"]) == 0
    assert capsys.readouterr().out.strip() == "wrote VALIDATION.md"
    assert (tmp_path / "VALIDATION.md").read_text() == "# stub\n"
    assert (ROOT / "VALIDATION.md").read_text() == before
