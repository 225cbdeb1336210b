"""A numba cache file cut short (a full disk, a killed process) is compiled again and
said once, not an UnpicklingError or EOFError in every run after (issue 36 item 6;
`beltmdsm.integrate._background._compile`)."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("numba")

ROOT = Path(__file__).resolve().parents[3]
NOTICE = "beltmdsm: numba's cache of the compiled integrators was unreadable"

#: A function numba caches on disk (cache=True needs a file), in a module of its own.
MODULE = """
import numba


@numba.njit(cache=True)
def twice(x):
    return 2.0 * x
"""

#: Compiled (or loaded) the way the integrators are, and called.
RUN = """
import twice_mod
from beltmdsm.integrate import _background

fn = _background._compile((lambda: twice_mod.twice, ()), (1.5,))
print(fn(1.5))
"""


def _run(tmp_path):
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), str(tmp_path / "src")]))
    env.update(NUMBA_CACHE_DIR=str(tmp_path / "numba"), BELTMDSM_CACHE=str(tmp_path / "cache"))
    done = subprocess.run(
        [sys.executable, "-c", RUN], env=env, cwd=ROOT, capture_output=True, text=True, timeout=300
    )
    return done.returncode, done.stdout.strip(), done.stderr


@pytest.mark.parametrize(("suffix", "keep"), [(".nbi", 0), (".nbc", 20)])
def test_a_truncated_cache_file_is_compiled_again_and_said_once(tmp_path, suffix, keep):
    (tmp_path / "src").mkdir()
    (tmp_path / "src" / "twice_mod.py").write_text(MODULE)
    assert _run(tmp_path) == (0, "3.0", "")
    (cached,) = (tmp_path / "numba").rglob(f"twice_mod.twice-*{suffix}")
    (index,) = (tmp_path / "numba").rglob("twice_mod.twice-*.nbi")
    cached.write_bytes(cached.read_bytes()[:keep])  # cut short
    rc, out, err = _run(tmp_path)
    assert (rc, out) == (0, "3.0"), err
    assert "Traceback" not in err
    (line,) = err.splitlines()
    assert line.startswith(NOTICE) and str(index) in line  # the entry it removed
    # written afresh: the next run loads it and says nothing
    assert _run(tmp_path) == (0, "3.0", "")


def test_a_failure_that_is_not_the_cache_goes_through(tmp_path):
    (tmp_path / "src").mkdir()
    bad = MODULE.replace("2.0 * x", "undefined_name * x")
    (tmp_path / "src" / "twice_mod.py").write_text(bad)
    rc, _, err = _run(tmp_path)
    assert rc == 1 and "TypingError" in err and NOTICE not in err
