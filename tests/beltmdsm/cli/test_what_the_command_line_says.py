"""Issue 28, "What the command line and API say" and "Output files checked late",
end to end: ``python -m beltmdsm ...`` in a subprocess, its exit status, stdout and
stderr.
"""

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from beltmdsm.model import Model
from beltmdsm.periodic.engines import period_map
from beltmdsm.periodic.floquet import floquet

ROOT = Path(__file__).resolve().parents[3]
ENV = {**os.environ, "PYTHONPATH": str(ROOT)}


def _cli(*argv, cwd=ROOT, timeout=120, module="beltmdsm"):
    return subprocess.run(
        [sys.executable, "-m", module, *argv],
        env=ENV,
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=timeout,
    )


def _refused(*argv, timeout=60, module="beltmdsm"):
    """``argv`` exits 2 with one line on stderr, nothing on stdout; the line.

    The timeout is far below what the refused commands computed before failing
    (``validate`` 100-120 s): the check comes first."""
    done = _cli(*argv, timeout=timeout, module=module)
    assert done.returncode == 2, (done.returncode, done.stderr)
    assert done.stdout == "" and "Traceback" not in done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1, done.stderr
    return lines[0]


# ------------------------------------------------------- output files checked early


@pytest.mark.parametrize(
    "argv",
    [
        ("check-paper", "--out", "/proc/P.md"),  # was a FileNotFoundError after 9 s
        ("--out", "/proc/gen"),  # derive's --out: after 12 s
        ("validate", "--out", "/proc/V.md"),  # computed 100-120 s, exit 1 ("[Errno 2]")
        ("sweep", "--param", "Vb", "--values", "3", "--out", "/proc/S.csv"),
        ("simulate", "--save", "/proc/run"),
    ],
)
def test_an_output_that_cannot_be_written_is_refused_first(argv):
    line = _refused(*argv)
    flag = [a for a in argv if a.startswith("--")][-1]
    assert f"argument {flag}: /proc/" in line and "cannot be written" in line, line


def test_check_paper_out_is_checked_from_derive_too():
    line = _refused("check-paper", "--out", "/proc/P.md", module="derive")
    assert "argument --out: /proc/P.md cannot be written" in line


# ------------------------------------------------------------- bounds named by flag


def test_floquet_periods_beyond_the_seed_names_the_flag_and_the_bound():
    line = _refused("floquet", "--periods", "128")
    assert "argument --periods: periods must be <= 127" in line, line
    assert "samples" not in line.split("periods must")[0]


def test_responses_and_coexistence_limits_name_the_flag_and_the_bound():
    line = _refused("responses", "--limit", "200")
    assert "error: argument --limit: limit must be <= 74, since the ladders" in line, line
    line = _refused("coexistence", "--param", "Vb", "--from", "3", "--to", "4", "--limit", "500")
    assert "argument --limit: limit must be <= 74" in line, line
    # the run of 10 s has 3 samples (T = pi/2 s at the base set: periods 4, 5, 6 of 6)
    line = _refused("responses", "--t-end", "10")
    assert "argument --limit/--t-end: a run of 10 s has 3 stroboscopic samples" in line, line
    need = np.ceil(25 / 0.4) * np.pi / 2
    # the flags, not the Python arguments (issue 36, item 15)
    assert f"give --t-end >= {need:.6g} s or --limit <= 1" in line, line


# -------------------------------------------------------- a lock at a divisor of K


def test_floquet_periods_8_reports_the_4t_response():
    # issue 28: "no response of 8 periods" though the 4T orbit is 8T-periodic
    done = _cli("floquet", "--periods", "8", "--Vb", "5")
    assert done.returncode == 0, done.stderr
    first = done.stdout.splitlines()[0]
    assert first.startswith("the response of 8 periods is the 4T response"), first
    eight = json.loads(_cli("floquet", "--periods", "8", "--Vb", "5", "--json").stdout)
    assert (eight["periods"], eight["periods_asked"]) == (4, 8)
    four = floquet(Model(Vb=5.0), periods=4)
    assert four.response.periods == 4 and eight["period"] == pytest.approx(four.period)
    got = np.array([complex(*z) for z in eight["multipliers"]])
    assert np.allclose(got, four.multipliers, atol=1e-9)
    # the orbit reported is a fixed point of the 8-fold map, as asked
    x = four.response.shooting_state
    assert np.allclose(period_map(Model(Vb=5.0), 8)(x).state, x, atol=1e-8)


# ------------------------------------------------------------ flags that did nothing


def test_perturbation_without_a_periodic_start_is_refused():
    line = _refused("simulate", "--perturbation", "0.1")
    assert "argument --perturbation:" in line and "--start periodic" in line, line


def test_save_says_the_file_it_wrote(tmp_path):
    # numpy.savez adds .npz: the name written is checked and printed
    done = _cli("simulate", "--t-end", "5", "--save", "run.dat", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines()[-1] == "samples written to run.dat.npz"
    with np.load(tmp_path / "run.dat.npz") as data:
        assert data["t"][-1] == pytest.approx(5.0) and data["X1"].shape == data["t"].shape
    assert not (tmp_path / "run.dat").exists()
    done = _cli("simulate", "--t-end", "5", "--save", "b.npz", "--json", cwd=tmp_path)
    assert json.loads(done.stdout)["saved"] == "b.npz" and (tmp_path / "b.npz").exists()


def test_a_closed_pipe_ends_quietly():
    # issue 28: `| head` ended "error: [Errno 32] Broken pipe"; the reader is gone
    # before the command writes its first line
    proc = subprocess.Popen(
        [sys.executable, "-m", "beltmdsm", "docs", "modelling"],
        env=ENV,
        cwd=ROOT,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    proc.stdout.close()
    err = proc.stderr.read().decode()
    assert proc.wait(timeout=60) == 1
    assert err == ""


# ------------------------------------------------------------- one rule, both caches


def test_an_empty_beltmdsm_cache_is_unset_for_the_sweeps(tmp_path):
    # issue 28: BELTMDSM_CACHE= wrote the sweep files into the current folder, and
    # only the compiled code honoured XDG_CACHE_HOME. Here the folder that the rule
    # gives cannot be written, so the sweep is refused (before computing) naming it.
    env = {**ENV, "BELTMDSM_CACHE": "", "XDG_CACHE_HOME": "/proc/x"}
    done = subprocess.run(
        [sys.executable, "-m", "beltmdsm", "sweep", "--param", "Vb", "--values", "3"],
        env=env,
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert done.returncode == 2, done.stderr
    assert "cache folder /proc/x/beltmdsm-cache/sweeps cannot be written" in done.stderr
    assert list(tmp_path.iterdir()) == []


def test_a_pipe_closed_before_the_last_flush_ends_quietly():
    # a short output stays in the buffer until the end: the flush meets the closed pipe
    env = {k: v for k, v in ENV.items() if k != "PYTHONUNBUFFERED"}
    proc = subprocess.Popen(
        [sys.executable, "-m", "beltmdsm", "docs"],
        env=env,
        cwd=ROOT,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    proc.stdout.close()
    err = proc.stderr.read().decode()
    assert proc.wait(timeout=60) == 1
    assert err == ""
