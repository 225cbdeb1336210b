"""The package as a user installs it (issue 17, section 4): built into a wheel,
installed (not editable) into a fresh virtual environment, run from another folder.

* every folder holding modules is in pyproject.toml's package list (it is listed so
  that docs/ ships inside the package; tests/test_docs.py checks that what the sources
  cite exists);
* installed, ``python -m derive`` refuses to regenerate the installed generated/ in one
  line, ``check-paper --out`` and ``validate --out`` choose where their reports go,
  and the documents the help texts cite print from the installed package;
* uninstalling leaves nothing behind (no stray ``generated/PAPER_CHECK.md`` that
  would make ``generated`` a broken namespace package).
"""

from __future__ import annotations

import re
import shutil
import site
import subprocess
import sys
import venv
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SOURCES = ("derive", "generated", "beltmdsm")


def test_every_module_folder_is_a_listed_package():
    tomllib = pytest.importorskip("tomllib")  # Python 3.11
    listed = set(
        tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["packages"]
    )
    folders = {
        ".".join(path.parent.relative_to(ROOT).parts)
        for top in SOURCES
        for path in (ROOT / top).rglob("*.py")
        if "__pycache__" not in path.parts
    }
    assert folders | {"beltmdsm.docs"} == listed


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    """A virtual environment (seeing this one's packages: numpy, sympy, ...) with the
    wheel of this checkout installed, and a folder outside the checkout to run in."""
    tmp = tmp_path_factory.mktemp("install")
    # built from a copy of the files git would commit: an in-tree build writes build/
    # and *.egg-info into the checkout, and a stale build/ can leak into a wheel
    listed = (
        subprocess.run(
            ["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
            cwd=ROOT,
            capture_output=True,
            check=True,
        )
        .stdout.decode()
        .split("\0")
    )
    source = tmp / "source"
    for rel in filter(None, listed):
        if (ROOT / rel).is_file():
            (source / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / rel, source / rel)
    build = subprocess.run(
        [sys.executable, "-m", "pip", "wheel", "-q", "--no-deps", "-w", tmp / "dist", source],
        capture_output=True,
        text=True,
    )
    if build.returncode and "setuptools" in build.stderr and "satisfies" in build.stderr:
        pytest.skip("pip cannot fetch setuptools to build the wheel (no package index)")
    assert build.returncode == 0, build.stderr
    env_dir = tmp / "env"
    venv.create(env_dir, with_pip=False)
    python = env_dir / "bin" / "python"
    env_site = Path(
        subprocess.run(
            [python, "-c", "import sysconfig; print(sysconfig.get_path('purelib'))"],
            capture_output=True,
            text=True,
            check=True,
        ).stdout.strip()
    )
    # this environment's dependencies (numpy, sympy, numba), as plain path entries:
    # its .pth files, among them the editable install of this checkout, stay unread
    (env_site / "dependencies.pth").write_text("\n".join(site.getsitepackages()) + "\n")
    wheel = next((tmp / "dist").glob("beltmdsm-*.whl"))
    pip = [sys.executable, "-m", "pip", "--python", python]
    subprocess.run([*pip, "install", "-q", "--no-deps", wheel], check=True)
    work = tmp / "work"
    work.mkdir()
    return python, pip, env_site, work


def _run(installed, *args):
    python, _, _, work = installed
    return subprocess.run(
        [python, "-m", *args], capture_output=True, text=True, cwd=work, timeout=600
    )


def test_the_installed_package_is_the_wheel(installed):
    _, _, purelib, _ = installed
    assert purelib != ROOT and (purelib / "generated" / "stability.py").is_file()
    assert (purelib / "derive" / "codegen" / "templates" / "_support.py").is_file()


def test_installed_derive_refuses_to_regenerate_the_package(installed):
    _, _, purelib, _ = installed
    before = {p: p.stat().st_mtime_ns for p in (purelib / "generated").rglob("*.py")}
    done = _run(installed, "derive")
    assert done.returncode == 2
    assert done.stderr.count("\n") == 1 and "needs a source checkout" in done.stderr
    assert "--out DIR" in done.stderr
    assert before == {p: p.stat().st_mtime_ns for p in (purelib / "generated").rglob("*.py")}


def test_installed_help_cites_documents_that_print(installed):
    help_text = _run(installed, "beltmdsm", "floquet-band", "--help").stdout
    cited = re.findall(r"docs/\w+\.md#[\w-]+", help_text)
    assert cited
    for name in cited:
        done = _run(installed, "beltmdsm", "docs", name)
        assert done.returncode == 0, done.stderr
        assert done.stdout.startswith("#") and len(done.stdout.splitlines()) > 3
    _, _, purelib, _ = installed
    listing = _run(installed, "beltmdsm", "docs").stdout
    assert str(purelib / "beltmdsm" / "docs") in listing


def test_installed_package_is_typed_licensed_and_versioned(installed):
    python, _, purelib, work = installed
    assert (purelib / "beltmdsm" / "py.typed").is_file()
    assert (purelib / "beltmdsm" / "__init__.pyi").is_file()
    dist = next(purelib.glob("beltmdsm-*.dist-info"))
    meta = (dist / "METADATA").read_text()
    assert "Classifier: License :: OSI Approved :: MIT License" in meta
    assert "Classifier: Typing :: Typed" in meta
    (license_,) = [p for p in dist.rglob("LICENSE*") if p.is_file()]
    assert license_.read_text() == (ROOT / "LICENSE").read_text()
    version = subprocess.run(
        [python, "-c", "import beltmdsm; print(beltmdsm.__version__)"],
        capture_output=True, text=True, check=True, cwd=work,
    ).stdout.strip()  # fmt: skip
    assert f"Version: {version}\n" in meta and version == _declared_version()


def _declared_version():
    return re.search(r'^version = "([^"]+)"', (ROOT / "pyproject.toml").read_text(), re.M)[1]


def test_the_citation_names_this_version_and_the_paper():
    cff = (ROOT / "CITATION.cff").read_text()
    assert f'\nversion: "{_declared_version()}"\n' in cff and "\nlicense: MIT\n" in cff
    readme = (ROOT / "README.md").read_text()  # the paper, as the README cites it
    title = "Parametric excitation and friction modulation for a forced 2-DOF system"
    assert title in readme and f'title: "{title}"' in cff


def test_installed_runs_write_outside_the_package_and_uninstall_is_clean(installed):
    python, pip, purelib, work = installed
    imported = _run(installed, "beltmdsm", "simulate", "--t-end", "20")
    assert imported.returncode == 0, imported.stderr
    where = subprocess.run(
        [
            python,
            "-c",
            "import beltmdsm.derive.paper_check as p, beltmdsm; print(p.report_path()); "
            "print(beltmdsm.__file__)",
        ],
        capture_output=True,
        text=True,
        check=True,
        cwd=work,
    ).stdout.split()
    assert (work / where[0]).resolve() == work.resolve() / "PAPER_CHECK.md"
    assert Path(where[1]).is_relative_to(purelib)
    done = _run(installed, "beltmdsm", "validate", "--out", str(work / "nowhere" / "V.md"))
    assert done.returncode == 2 and "--out" in done.stderr
    subprocess.run([*pip, "uninstall", "-q", "-y", "beltmdsm"], check=True)
    left = [p for top in SOURCES if (purelib / top).exists() for p in (purelib / top).rglob("*")]
    assert left == []
