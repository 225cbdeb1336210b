"""What the README and the docs state about the package, against the code (issue 37
items 1 and 5): the cache folder they name, the dependencies the README's install
gives, the figures of time they quote."""

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def test_the_dask_page_names_the_cache_folder_the_code_uses(monkeypatch, tmp_path):
    from beltmdsm.batch.cache import default_cache_dir

    text = (ROOT / "docs" / "howto" / "dask.md").read_text()
    monkeypatch.delenv("BELTMDSM_CACHE", raising=False)
    monkeypatch.delenv("XDG_CACHE_HOME", raising=False)
    monkeypatch.setenv("HOME", str(tmp_path))
    home = default_cache_dir().relative_to(tmp_path).as_posix()
    assert f"`~/{home}`" in text
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    xdg = default_cache_dir().relative_to(tmp_path / "xdg").as_posix()
    assert f"`$XDG_CACHE_HOME/{xdg}`" in text
    monkeypatch.setenv("BELTMDSM_CACHE", str(tmp_path / "own"))
    own = default_cache_dir().relative_to(tmp_path / "own").as_posix()
    assert f"`$BELTMDSM_CACHE/{own}`" in text
    # no other spelling of the folder anywhere in the docs
    for page in (ROOT / "docs").rglob("*.md"):
        assert not re.search(r"\.cache/beltmdsm/", page.read_text()), page


def test_the_readme_states_what_derive_prints_and_installs_the_fast_package():
    """Issue 37 item 1: the README said "of 24" (derive writes 27 files) and "about
    20 s" (39-47 s of CPU measured), and its install line gave no numba and no
    matplotlib, so that every run took the plain-Python path, 14 times slower."""
    tomllib = pytest.importorskip("tomllib")  # Python 3.11
    readme = (ROOT / "README.md").read_text()
    written = len([p for p in (ROOT / "generated").rglob("*.py") if "__pycache__" not in p.parts])
    for text in (readme, (ROOT / "docs" / "howto" / "regenerate.md").read_text()):
        (n,) = re.findall(r"wrote 0 changed file\(s\) of (\d+)\.", text)
        assert int(n) == written
    assert "about 20 s" not in readme and "about a minute of one core" in readme
    deps = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["dependencies"]
    names = {re.match(r"[\w-]+", d)[0] for d in deps}
    assert {"numba", "matplotlib", "sympy", "numpy", "scipy", "tqdm"} <= names
    # the first command installs no extra: the fast package is the default
    assert re.search(r"```bash\npython -m pip install -e \. ", readme)


def test_the_notebook_pages_state_the_times_measured():
    """The first-hour page said "about 10 s" (49 s measured) and json.md "about 15 s"
    (58 s): figures of one core's time, measured by running their cells."""
    first = (ROOT / "docs" / "tutorials" / "first_hour.md").read_text()
    assert "about 10 s" not in first and "about 15 s of one core" in first
    assert '".[plot]"' not in first  # matplotlib comes with the package
    json_page = (ROOT / "docs" / "reference" / "json.md").read_text()
    assert "about 15 s" not in json_page and "about 30 s of one core" in json_page


def test_the_readme_command_for_another_model_prints_what_the_readme_says():
    """The README's paragraph on other friction oscillators: its command runs, and finds
    the Hopf point and the onset of stick the paragraph states (the Hopf point is also the
    closed form it quotes, with belt_1dof's defaults)."""
    import math
    import os
    import subprocess
    import sys

    from beltmdsm.other_model import model_module

    readme = (ROOT / "README.md").read_text()
    (line,) = re.findall(r"^python -m beltmdsm branch --model belt_1dof.*$", readme, re.M)
    done = subprocess.run(
        [sys.executable, *line.split()[1:]], capture_output=True, text=True,
        env={**os.environ, "MPLBACKEND": "Agg"}, timeout=300,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-2000:]
    hopf = re.search(r"Vb = 1\.995720201 \(in closed form", readme)
    onset = re.search(r"onset of stick at Vb = (\d\.\d+)\.", readme)
    assert hopf and onset
    assert "Hopf points 1.995720201" in done.stdout
    printed = float(re.search(r"stick onset at Vb = ([\d.]+)", done.stdout).group(1))
    assert round(printed, 4) == float(onset.group(1))
    d = model_module("belt_1dof").DEFAULTS  # the closed form the README quotes
    closed = d["v_s"] * math.log(
        d["g"] * (d["mu_s"] - d["mu_k"]) / (2 * d["beta1"] * d["omega1"] * d["v_s"])
    )
    assert f"{closed:.9f}" == "1.995720201"
