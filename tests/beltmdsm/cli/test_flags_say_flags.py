"""Issue 36, items 14, 15 and 18, through the command line (``python -m beltmdsm``, run
in the test's process, tests/inprocess.py; a real process where a time bound matters):
negative numbers in scientific notation are flag values; an error names the flags the
user typed, not the Python arguments behind them; a start beyond floating point is
refused by its flags instead of "[], 4 unidentified", exit 0.
"""

import subprocess
import sys
from pathlib import Path

import pytest
from inprocess import cli as _cli

ROOT = Path(__file__).resolve().parents[3]


def _refused(*argv):
    """``argv`` exits 2 with one line on stderr; the line."""
    done = _cli(*argv)
    assert done.returncode == 2, (done.returncode, done.stderr)
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1, done.stderr
    return lines[0]


def test_a_negative_number_in_scientific_notation_is_a_value():
    # "argument --phase_t: expected one argument" before
    done = _cli("simulate", "--phase_t", "-1e-3", "--t-end", "2", "--json")
    assert done.returncode == 0, done.stderr
    assert '"phase_t": -0.001' in done.stdout
    # the value reaches basins' range check: refused for --points, not for the number
    line = _refused("basins", "--x-from", "-1e-2", "--x-to", "-2E-3", "--points", "1")
    assert "expected one argument" not in line and "--points" in line


@pytest.mark.parametrize(
    "argv, says, not_says",
    [
        (
            ("lyapunov", "--t-end", "100", "--t-transient", "500"),
            ["--t-transient must be", "< --t-end (100)"],
            ["t_transient", "t_end"],
        ),
        (
            ("simulate", "--t-end", "1e-6"),
            ["--t-discard must be", "--dt (0.02)", "before --t-end (1e-06)"],
            ["t_discard", "t_end=", "None"],
        ),
        (
            # a model parameter stays the model's word, a formula stays a formula
            ("sweep", "--param", "Vb", "--values", "3", "--dt", "0.7", "--t-end", "50"),
            ["argument --dt: at Vb = 3: --dt = 0.7 s", "pi/dt = ", "use --dt <= 0.09817"],
            ["--Vb", "pi/--dt"],
        ),
        (
            ("basins", "--t-end", "16", "--no-cache"),
            ["--t-end must be at least 22 excitation periods", "got 16"],
            ["t_discard", "t_end"],
        ),
    ],
)
def test_an_error_names_the_flags_typed(argv, says, not_says):
    line = _refused(*argv)
    for text in says:
        assert text in line, line
    for text in not_says:
        assert text not in line, line


def test_a_start_beyond_floating_point_is_refused_by_its_flags():
    # it was iterated for 36 s and printed "[], 4 unidentified", exit 0: a real process,
    # bounded in time
    done = subprocess.run(
        [sys.executable, "-m", "beltmdsm", "basins", "--x-from", "1e300", "--x-to", "1e301"]
        + ["--points", "2"],
        cwd=ROOT, capture_output=True, text=True, timeout=30,
    )  # fmt: skip
    assert done.returncode == 2, (done.returncode, done.stderr)
    assert len(done.stderr.strip().splitlines()) == 1, done.stderr
    line = done.stderr.strip()
    assert line.startswith("python -m beltmdsm basins: error: argument --x-from/--x-to: ")
    assert "X1 = 1e+300 is beyond floating point" in line and "choose |X1| < " in line
