"""The package as a user installs it (issue 17, section 4): built into a wheel,
installed (not editable) into a fresh virtual environment, run from another folder.

* every folder holding modules is in pyproject.toml's package list (it is listed so
  that docs/, generated/ and derive/ ship inside the package; tests/test_docs.py checks
  that what the sources cite exists);
* the wheel installs one top-level name, ``beltmdsm``: run from a folder that holds a
  user's own ``generated/`` package and ``derive.py``, nothing of theirs is imported;
* installed, the derivation (``beltmdsm`` with no command) refuses to regenerate the
  installed generated/ in one line, ``check-paper --out`` and ``validate --out``
  choose where their reports go, and the documents the help texts cite print from the
  installed package;
* uninstalling leaves nothing behind (no stray ``generated/PAPER_CHECK.md`` that
  would make ``beltmdsm.generated`` a broken namespace package).
"""

from __future__ import annotations

import functools
import json
import os
import re
import shutil
import site
import subprocess
import sys
import venv
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
#: Each package and its folder in the checkout (pyproject.toml's package-dir).
SOURCES = {"beltmdsm": "beltmdsm", "beltmdsm.derive": "derive", "beltmdsm.generated": "generated"}


def test_every_module_folder_is_a_listed_package():
    tomllib = pytest.importorskip("tomllib")  # Python 3.11
    listed = set(
        tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["packages"]
    )
    folders = {
        ".".join((package, *path.parent.relative_to(ROOT / folder).parts))
        for package, folder in SOURCES.items()
        for path in (ROOT / folder).rglob("*.py")
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


#: The environment of the installed runs: no PYTHONPATH (a checkout on it would be
#: imported instead of the installed package).
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}


def _run(installed, *args):
    python, _, _, work = installed
    return subprocess.run(
        [python, "-m", *args], capture_output=True, text=True, cwd=work, timeout=600, env=ENV
    )


def test_the_installed_package_is_the_wheel(installed):
    _, _, purelib, _ = installed
    package = purelib / "beltmdsm"
    assert purelib != ROOT and (package / "generated" / "stability.py").is_file()
    assert (package / "derive" / "codegen" / "templates" / "_support.py").is_file()


def test_the_wheel_installs_one_top_level_name(installed):
    """Everything a user imports is under ``beltmdsm`` (issue 30): the wheel's files
    (its RECORD) are the package and its dist-info, and the console script."""
    _, _, purelib, _ = installed
    (dist,) = purelib.glob("beltmdsm-*.dist-info")
    names = [line.split(",")[0] for line in (dist / "RECORD").read_text().splitlines()]
    tops = {name.split("/")[0] for name in names if not name.startswith("..")}
    assert tops == {"beltmdsm", dist.name}
    assert not (purelib / "generated").exists() and not (purelib / "derive").exists()


#: A user's folder: a ``generated/`` package of their own, and a ``derive.py`` that
#: fails loudly if imported.
USER_FILES = {
    "generated/__init__.py": "",
    "derive.py": "raise RuntimeError('the user\\'s own derive.py was imported')\n",
}

#: Touches beltmdsm.generated (the model's parameters, the unforced equilibrium),
#: printing where they came from.
USER_SCRIPT = """
import json, sys
import beltmdsm
from beltmdsm.generated import unforced
model = beltmdsm.Model(Vb=5)
print(json.dumps(dict(
    generated=beltmdsm.generated.__file__,
    X1=float(unforced.equilibrium(**model.arguments(unforced.equilibrium))[0]),
    params=dict(model.params),
    user=sorted(m for m in sys.modules if m.split(".")[0] in ("generated", "derive")),
)))
"""


def test_a_users_own_generated_and_derive_do_not_shadow_the_package(installed, tmp_path):
    """Issue 30: run from a folder holding ``generated/`` and ``derive.py`` (the first
    entry of ``sys.path`` for ``python -m`` and ``-c``), the installed package imports
    its own modules and none of the user's."""
    python, _, purelib, _ = installed
    for rel, text in USER_FILES.items():
        (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / rel).write_text(text)
    run = functools.partial(
        subprocess.run, capture_output=True, text=True, cwd=tmp_path, env=ENV, timeout=600
    )
    help_ = run([python, "-m", "beltmdsm", "--help"])
    assert help_.returncode == 0, help_.stderr
    assert "simulate" in help_.stdout and "check-paper" in help_.stdout
    done = run([python, "-c", USER_SCRIPT])
    assert done.returncode == 0, done.stderr
    got = json.loads(done.stdout)
    assert Path(got["generated"]).parent == purelib / "beltmdsm" / "generated"
    assert got["user"] == []
    # the unforced equilibrium of Coulomb's law, X1 = mu_s g / omega1^2 (Eq. 9)
    p = got["params"]
    assert got["X1"] == pytest.approx(p["mu_s"] * p["g"] / p["omega1"] ** 2, rel=1e-14)


def test_installed_derivation_refuses_to_regenerate_the_package(installed):
    _, _, purelib, _ = installed
    generated = purelib / "beltmdsm" / "generated"
    before = {p: p.stat().st_mtime_ns for p in generated.rglob("*.py")}
    done = _run(installed, "beltmdsm", "--regenerate")
    assert done.returncode == 2
    assert done.stderr.count("\n") == 1 and "needs a source checkout" in done.stderr
    assert "--out DIR" in done.stderr
    assert before == {p: p.stat().st_mtime_ns for p in generated.rglob("*.py")}


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


#: Every command's help text, printed by the installed package.
HELP_TEXTS = """
import argparse
from beltmdsm.cli.tree import build_parser
parser = build_parser()
print(parser.format_help())
for action in parser._actions:
    if isinstance(action, argparse._SubParsersAction):
        for sub in action.choices.values():
            print(sub.format_help())
"""


def test_the_wheel_carries_every_page_the_help_texts_cite_and_no_docs_conf(installed):
    """Issue 37 item 5: ``--json`` cited docs/reference/json.md, which the wheel lacked,
    and the wheel shipped the site's docs/conf.py as a module, ``beltmdsm.docs.conf``."""
    python, _, purelib, work = installed
    docs = purelib / "beltmdsm" / "docs"
    assert not (docs / "conf.py").exists() and (docs / "reference" / "json.md").is_file()
    assert not list(docs.rglob("*.py"))  # no module of the site (docs/_ext) either
    helps = subprocess.run(
        [python, "-c", HELP_TEXTS], capture_output=True, text=True, cwd=work, env=ENV
    )
    assert helps.returncode == 0, helps.stderr
    # argparse wraps lines after a hyphen too: joined again; PAGE/SECTION are placeholders
    text = re.sub(r"-\n\s+", "-", helps.stdout)
    cited = set(re.findall(r"docs/[a-z0-9_/]+\.md(?:#[a-z0-9_-]+)?", text))
    assert "docs/reference/json.md" in cited
    for name in sorted(cited):
        done = _run(installed, "beltmdsm", "docs", name)
        assert done.returncode == 0, done.stderr
        assert re.search(r"^#+ ", done.stdout, re.M), name


def test_installed_package_is_typed_licensed_and_versioned(installed):
    python, _, purelib, work = installed
    assert (purelib / "beltmdsm" / "py.typed").is_file()
    assert (purelib / "beltmdsm" / "__init__.pyi").is_file()
    dist = next(purelib.glob("beltmdsm-*.dist-info"))
    meta = (dist / "METADATA").read_text()
    # the license as an SPDX expression (PEP 639; issue 37 item 5), not a classifier
    assert "License-Expression: MIT\n" in meta and "Classifier: License ::" not in meta
    assert "Classifier: Typing :: Typed" in meta
    (license_,) = [p for p in dist.rglob("LICENSE*") if p.is_file()]
    assert license_.read_text() == (ROOT / "LICENSE").read_text()
    version = subprocess.run(
        [python, "-c", "import beltmdsm; print(beltmdsm.__version__)"],
        capture_output=True, text=True, check=True, cwd=work, env=ENV,
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
        env=ENV,
    ).stdout.split()
    assert (work / where[0]).resolve() == work.resolve() / "PAPER_CHECK.md"
    assert Path(where[1]).is_relative_to(purelib)
    done = _run(installed, "beltmdsm", "validate", "--out", str(work / "nowhere" / "V.md"))
    assert done.returncode == 2 and "--out" in done.stderr
    subprocess.run([*pip, "uninstall", "-q", "-y", "beltmdsm"], check=True)
    left = list((purelib / "beltmdsm").rglob("*"))
    assert left == []


def _sdist_files(tmp_path):
    """This checkout's source distribution, built as a user builds it, unpacked."""
    pytest.importorskip("build")
    source = _copy_of_checkout(tmp_path / "source")
    done = subprocess.run(
        [sys.executable, "-m", "build", "--sdist", "-o", tmp_path / "dist", source],
        capture_output=True,
        text=True,
    )
    if done.returncode and "setuptools" in done.stderr and "satisf" in done.stderr:
        pytest.skip("cannot fetch setuptools to build the sdist (no package index)")
    assert done.returncode == 0, done.stderr
    # setuptools' own warnings (the license's form): none
    assert "SetuptoolsDeprecationWarning" not in done.stderr, done.stderr
    (sdist,) = (tmp_path / "dist").glob("beltmdsm-*.tar.gz")
    import tarfile

    with tarfile.open(sdist) as tar:
        tar.extractall(tmp_path / "unpacked", filter="data")
    (top,) = (tmp_path / "unpacked").iterdir()
    return top


def _copy_of_checkout(source):
    listed = subprocess.run(
        ["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
        cwd=ROOT,
        capture_output=True,
        check=True,
    ).stdout.decode()
    for rel in filter(None, listed.split("\0")):
        if (ROOT / rel).is_file():
            (source / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / rel, source / rel)
    return source


@pytest.fixture(scope="module")
def sdist(tmp_path_factory):
    """``(unpacked sdist, the copy of the checkout it was built from)``."""
    tmp = tmp_path_factory.mktemp("sdist")
    return _sdist_files(tmp), tmp / "source"


def test_the_sdist_carries_what_rebuilds_and_tests_the_package(sdist):
    """Issue 37 item 5: the sdist had 6 of 81 test files, and 38 tests failed from it."""
    top, source = sdist
    wanted = {
        p.relative_to(source).as_posix()
        for folder in ("tests", "notebooks", "docs", "benchmarks")
        for p in (source / folder).rglob("*")
        if p.is_file()
    } | {"CITATION.cff", "VALIDATION.md", "README.md", "LICENSE", "generated/PAPER_CHECK.md"}
    shipped = {p.relative_to(top).as_posix() for p in top.rglob("*") if p.is_file()}
    assert wanted - shipped == set()


@pytest.mark.slow
def test_the_tests_that_read_the_files_around_the_package_pass_from_the_sdist(sdist):
    top, _ = sdist
    env = {**ENV, "PYTHONPATH": str(top)}
    done = subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-m", "not slow",
         "tests/test_docs.py", "tests/test_layers.py", "tests/test_notebooks_clean.py",
         "tests/test_install.py::test_every_module_folder_is_a_listed_package",
         "tests/test_install.py::test_the_citation_names_this_version_and_the_paper"],
        cwd=top, env=env, capture_output=True, text=True, timeout=900,
    )  # fmt: skip
    assert done.returncode == 0, done.stdout[-3000:]
    assert " passed" in done.stdout and "failed" not in done.stdout
