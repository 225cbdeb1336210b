"""The README followed literally in a fresh virtual environment (issue 37 item 1): its
install line gives the fast package (numba, so that the integrators compile, and
matplotlib, which its Python example draws with), and that example prints what the
README says it prints.

The second test is slow (it downloads and installs the dependencies, then runs the example cold):
``python -m pytest -m slow tests/test_readme_fresh_venv.py``. It needs the package index.
"""

import re
import shutil
import subprocess
import venv
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text()


def _blocks(language):
    return re.findall(rf"```{language}\n(.*?)```", README, re.S)


def _install_line():
    """The README's first command, its install part: ``python -m pip install -e . ...``."""
    first = _blocks("bash")[0].strip()
    return first.split("&&")[0].split()


def test_the_install_line_comes_first_and_names_no_extra():
    # the fast package is the default: no extra needed for numba or matplotlib
    line = _install_line()
    assert line[:5] == ["python", "-m", "pip", "install", "-e"] and line[5] == "."


def _copy_of_checkout(to):
    listed = subprocess.run(
        ["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
        cwd=ROOT, capture_output=True, check=True,
    ).stdout.decode()  # fmt: skip
    for rel in filter(None, listed.split("\0")):
        if (ROOT / rel).is_file():
            (to / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / rel, to / rel)
    return to


@pytest.mark.slow
def test_the_readme_in_a_fresh_venv_gives_the_fast_package_and_its_example_runs(tmp_path):
    clone = _copy_of_checkout(tmp_path / "clone")
    venv.create(tmp_path / "env", with_pip=True)
    python = str(tmp_path / "env" / "bin" / "python")
    line = _install_line()
    done = subprocess.run(
        [python, *line[1:]], cwd=clone, capture_output=True, text=True, timeout=1800
    )
    if done.returncode and "No matching distribution" in done.stderr + done.stdout:
        pytest.skip("no package index reachable")
    assert done.returncode == 0, done.stderr[-3000:]
    have = subprocess.run(
        [python, "-c", "import numba, matplotlib; print('ok')"],
        capture_output=True, text=True, cwd=tmp_path,
    )  # fmt: skip
    assert have.stdout.strip() == "ok", have.stderr
    example = _blocks("python")[0]
    (tmp_path / "work").mkdir()
    ran = subprocess.run(
        [python, "-c", example], cwd=tmp_path / "work", capture_output=True, text=True,
        timeout=1800,
    )  # fmt: skip
    assert ran.returncode == 0, ran.stderr[-3000:]
    printed = README.split("```python", 1)[1].split("prints\n\n```\n", 1)[1].split("```")[0]
    assert ran.stdout == printed
    assert (tmp_path / "work" / "band_branch.png").stat().st_size > 10_000
    # no process of it left: its compile, if any, ended with it (issue 37 item 1)
    left = subprocess.run(["pgrep", "-f", str(tmp_path)], capture_output=True, text=True)
    assert left.stdout.strip() == ""
