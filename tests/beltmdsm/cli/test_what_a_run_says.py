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

from beltmdsm.cli import main

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
    from beltmdsm import simulate as simulate_module

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
    for solver in ("events", "superposition"):
        line = _one_line_error(
            capsys, ["simulate", "--rtol", "1", "--solver", solver], "--rtol/--atol", "rtol = 1"
        )
        assert "step fell below the rounding of the time" in line


# ---------------------------------------------------------------- 7. bounded work


def test_a_run_too_large_for_memory_is_refused_before_computing(capsys, monkeypatch):
    from beltmdsm import simulate as simulate_module

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
        (["simulate", "--rtol", "1"], "--rtol/--atol"),
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
        [sys.executable, "-m", "beltmdsm", "simulate", "--alpha", "0", "--t-end", "300"],
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
            "multiplier; unstable above)",
            "existence; unstable on both sides)",
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
