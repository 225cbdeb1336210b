"""Every file that the repository's text cites exists in the repository.

Docstrings, comments, Markdown and notebooks are read by users who have only this
repository. This test scans the prose of every ``.py`` file (docstrings and
comments; other strings are data, e.g. a path a test creates), ``.md`` file and
``.ipynb`` file (Markdown cells, and the comments and docstrings of code cells) for

* paths under the package's folders (``docs/``, ``derive/``, ``beltmdsm/``,
  ``generated/``, ``tests/``, ``benchmarks/``, ``notebooks/``) and bare Markdown
  names (``README.md``): each must exist, relative to the repository root or to the
  citing file (a Markdown link);
* an anchor after a Markdown file name and ``#``: the file must have a heading
  with that anchor, by
  GitHub's rule (lowercase; punctuation other than ``-`` and ``_`` dropped; spaces
  become ``-``; repeated headings get ``-1``, ``-2``, ...).

The README is one screen; the site (docs/) holds the command list and the laws table, and
tests/test_docs_site.py checks them against the code.
"""

import ast
import io
import json
import os
import re
import tokenize
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
# _build: a Sphinx build folder (Sphinx copies the notebooks there, executed)
SKIP_DIRS = {"__pycache__", "build", "dist", "_build"}
SUFFIXES = {".py", ".md", ".ipynb"}
FOLDERS = ("docs", "derive", "beltmdsm", "generated", "tests", "benchmarks", "notebooks")

#: A path under one of the package's folders, not itself part of a longer path or URL.
PATH = re.compile(r"(?<![\w./~$-])((?:" + "|".join(FOLDERS) + r")/[\w./-]*[\w/])")
#: A Markdown file name, with an optional path and anchor.
MD = re.compile(r"(?<![\w./~$-])((?:\.\./|[\w-]+/)*[\w-]+\.md)(?:#([\w-]+))?(?![\w-])")


def repository_files():
    """The repository's text files (hidden folders, caches and build output skipped)."""
    for folder, dirs, files in os.walk(ROOT):
        dirs[:] = sorted(
            d for d in dirs if not (d.startswith(".") or d in SKIP_DIRS or d.endswith(".egg-info"))
        )
        for name in sorted(files):
            path = Path(folder) / name
            # a link (the docs build links notebooks/ into docs/tutorials/) is the file
            # it points to, read where it is
            if not name.startswith(".") and path.suffix in SUFFIXES and not path.is_symlink():
                yield path


FILES = list(repository_files())
NAMES = {p.name for p in FILES if p.suffix == ".md"}


def github_anchors(markdown: str) -> set[str]:
    """Anchors GitHub gives the headings of a Markdown text (code blocks skipped)."""
    anchors, seen, fenced = set(), {}, False
    for line in markdown.splitlines():
        if line.lstrip().startswith("```"):
            fenced = not fenced
            continue
        m = None if fenced else re.match(r"#{1,6}\s+(.*?)\s*#*\s*$", line)
        if not m:
            continue
        text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", m.group(1))  # link text only
        slug = re.sub(r"[^\w\- ]", "", text.lower()).replace(" ", "-")
        n = seen.get(slug, 0)
        seen[slug] = n + 1
        anchors.add(slug if n == 0 else f"{slug}-{n}")
    return anchors


def test_github_anchor_rule():
    text = "# Two readings of V_hat\n## The sign: paper or Eq. (4)?\n## Stick\n## Stick\n"
    assert github_anchors(text) == {
        "two-readings-of-v_hat",
        "the-sign-paper-or-eq-4",
        "stick",
        "stick-1",
    }


def resolve(cited: str, source: Path) -> Path | None:
    """The cited path, relative to the root or to the citing file; None if neither exists."""
    for base in (ROOT, source.parent):
        candidate = (base / cited).resolve()
        if candidate.exists() and (candidate == ROOT or ROOT in candidate.parents):
            return candidate
    return None


def python_prose(source: str) -> str:
    """Docstrings and comments of Python source."""
    parts = []
    try:
        tree = ast.parse(source)
    except SyntaxError:  # a notebook cell with IPython magics
        tree = None
    if tree is not None:
        for node in ast.walk(tree):
            if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
                parts.append(ast.get_docstring(node, clean=False) or "")
    try:
        tokens = tokenize.generate_tokens(io.StringIO(source).readline)
        parts += [t.string for t in tokens if t.type == tokenize.COMMENT]
    except (tokenize.TokenError, IndentationError, SyntaxError):
        parts += re.findall(r"#.*", source)
    return "\n".join(parts)


def prose(path: Path) -> str:
    """The text of a file that a reader reads as prose."""
    text = path.read_text(encoding="utf-8")
    if path.suffix == ".py":
        return python_prose(text)
    if path.suffix == ".ipynb":
        cells = json.loads(text)["cells"]
        return "\n".join(
            "".join(c["source"])
            if c["cell_type"] == "markdown"
            else python_prose("".join(c["source"]))
            for c in cells
        )
    return text


def citations(path: Path):
    """``(cited path, anchor or None)`` for each citation in one file."""
    text = prose(path)
    for m in PATH.finditer(text):
        cited = m.group(1).rstrip(".")
        if not cited.endswith(".md"):  # Markdown files: the second pattern
            yield cited, None
    for m in MD.finditer(text):
        yield m.group(1), m.group(2)
    if path.suffix == ".md":  # links to a heading of the same file
        for m in re.finditer(r"\]\(#([\w-]+)\)", text):
            yield str(path), m.group(1)


def problems(path: Path) -> list[str]:
    """What ``path`` cites that the repository lacks: files, and anchors of headings."""
    missing = []
    for cited, anchor in citations(path):
        if cited == str(path):
            target = path
        elif "/" not in cited and cited.endswith(".md"):
            if cited not in NAMES:
                missing.append(cited)
            target = next((p for p in (ROOT / cited, path.parent / cited) if p.exists()), None)
        else:
            target = resolve(cited, path)
            if target is None:
                missing.append(cited)
        if anchor and target is not None and target.is_file():
            if anchor not in github_anchors(target.read_text(encoding="utf-8")):
                name = path.name if target == path else cited
                missing.append(f"{name}#{anchor} (no such heading)")
    return sorted(set(missing))


@pytest.mark.parametrize("path", FILES, ids=lambda p: str(p.relative_to(ROOT)))
def test_cited_files_exist(path):
    missing = problems(path)
    assert not missing, (
        f"{path.relative_to(ROOT)} cites what the repository does not have: {missing}"
    )


def test_missing_files_and_anchors_are_found(tmp_path):
    doc = tmp_path / "doc.md"
    doc.write_text(
        "# Title\n\nSee [below](#nowhere), `derive/nothing.py`, `OTHER.md`,\n"
        "`docs/modelling.md#no-such-heading` and `docs/modelling.md#vhat`.\n"
    )
    assert problems(doc) == [
        "OTHER.md",
        "derive/nothing.py",
        "doc.md#nowhere (no such heading)",
        "docs/modelling.md#no-such-heading (no such heading)",
    ]


def test_modelling_notes_are_cited():
    """docs/modelling.md exists, and the package cites it (it replaced external notes)."""
    doc = ROOT / "docs" / "modelling.md"
    assert doc.is_file()
    anchors = github_anchors(doc.read_text(encoding="utf-8"))
    cited = {a for p in FILES for c, a in citations(p) if c.endswith("modelling.md") and a}
    assert cited and cited <= anchors


# The README is one screen; the site holds the command list and the laws table, checked by
# tests/test_docs_site.py (test_the_reference_covers_the_public_api_and_the_command_line,
# test_the_laws_page_is_the_registry).


def _headings():
    """``(file, heading)`` of every Markdown heading of docs/ and of the notebooks."""
    for path in sorted((ROOT / "docs").rglob("*.md")):
        fence = False
        for line in path.read_text(encoding="utf-8").splitlines():
            fence ^= line.startswith("```")
            if not fence and line.startswith("#"):
                yield path.relative_to(ROOT).as_posix(), line
    for path in sorted((ROOT / "notebooks").glob("*.ipynb")):
        for cell in json.loads(path.read_text(encoding="utf-8"))["cells"]:
            if cell["cell_type"] == "markdown":
                for line in cell["source"]:
                    if line.startswith("#"):
                        yield path.relative_to(ROOT).as_posix(), line.rstrip()


def test_headings_are_plain_text():
    """Issue 37 item 4: a heading is a page title and a sidebar entry, where TeX shows
    raw (``\\(V_b\\)``): headings spell symbols as the package does (``Vb``, ``X1'``)."""
    assert [h for h in _headings() if "$" in h[1] or "\\(" in h[1]] == []


def test_every_formula_of_the_notebooks_is_drawn_at_build():
    """The site pre-renders math with matplotlib's mathtext (docs/_ext/mathtext_math.py):
    a formula it cannot parse would fail the build, so each is tried here, offline."""
    import sys

    pytest.importorskip("matplotlib")
    sys.path.insert(0, str(ROOT / "docs" / "_ext"))
    from mathtext_math import svg

    formulas = {
        a or b
        for path in sorted((ROOT / "notebooks").glob("*.ipynb"))
        for cell in json.loads(path.read_text(encoding="utf-8"))["cells"]
        if cell["cell_type"] == "markdown"
        for a, b in re.findall(r"\$\$(.+?)\$\$|\$(.+?)\$", "".join(cell["source"]), re.S)
    }
    assert len(formulas) > 50
    drawn = {f: svg(f) for f in formulas}
    assert all(s.startswith("<svg") and "<path" in s for s in drawn.values())
    assert svg("V_b") == svg("V_b")  # the same text at every build
