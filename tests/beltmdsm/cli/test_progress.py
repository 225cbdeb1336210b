"""Progress on a terminal for the long commands (issue 36 item 12): ``basins`` (90 000
starts ran for minutes silently) and ``lyapunov`` show a bar on stderr once they have
taken 2 s, and Ctrl-C on ``basins`` says how many starts finished and where they are
kept. The commands run on a pseudo-terminal, as in a shell (a bar goes to a terminal
only, not into a pipe or a log)."""

from __future__ import annotations

import fcntl
import os
import pty
import re
import signal
import struct
import subprocess
import sys
import termios
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
ENV = {**os.environ, "PYTHONPATH": str(ROOT)}


def _until_bar_then_ctrl_c(argv, desc, limit=300):
    """Run ``beltmdsm ARGV`` with stderr on a terminal; once the bar ``desc:`` shows,
    Ctrl-C. ``(exit status, stderr as the terminal showed it)``."""
    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 120, 0, 0))
    proc = subprocess.Popen(
        [sys.executable, "-m", "beltmdsm", *argv],
        stdout=subprocess.DEVNULL,
        stderr=slave,
        env=ENV,
        cwd=ROOT,
        start_new_session=True,
    )
    os.close(slave)
    seen, sent = b"", False
    deadline = time.monotonic() + limit
    try:
        while time.monotonic() < deadline:
            try:
                chunk = os.read(master, 4096)
            except OSError:  # the terminal closed: the command ended
                break
            if not chunk:
                break
            seen += chunk
            if not sent and re.search(rf"{desc}: +\d+%\|".encode(), seen):
                os.killpg(proc.pid, signal.SIGINT)
                sent = True
        proc.wait(timeout=60)
    finally:
        os.close(master)
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    assert sent, f"no {desc} bar: {seen[-500:]!r}"
    return proc.returncode, seen.decode(errors="replace")


def test_basins_shows_its_starts_and_ctrl_c_says_what_it_kept(tmp_path):
    argv = ["basins", "--Vb", "3.88", "--points", "60", "--jobs", "1"]
    rc, err = _until_bar_then_ctrl_c([*argv, "--cache-dir", str(tmp_path)], "basins")
    assert rc == 130
    (line,) = [ln for ln in err.splitlines() if "interrupted" in ln]
    done = re.search(r"basins: stopped after (\d+) of (\d+) starts; every start finished is "
                     r"kept in the cache \((.*)\)\)$", line)  # fmt: skip
    assert done and int(done[2]) == 60 * 60 and done[3] == str(tmp_path), line
    assert int(done[1]) <= len(list(tmp_path.glob("*.json")))


def test_lyapunov_shows_the_simulated_time(tmp_path):
    rc, err = _until_bar_then_ctrl_c(["lyapunov", "--Vb", "4", "--t-end", "20000"], "lyapunov")
    assert rc == 130 and "s of simulated time" in err
