"""``docs``: print the documents the help texts cite (docs/*.md), installed or not.

The help texts and docstrings cite ``docs/modelling.md#tension`` and the like. In a
source checkout these are the files under ``docs/``; an installed package carries the
same files in its own folder ``docs`` (pyproject.toml maps the folder there), so that
every citation can be read where the package runs: ``beltmdsm docs docs/modelling.md#tension``
prints that section, ``beltmdsm docs modelling`` the whole page, ``beltmdsm docs`` the
list of pages and sections.
"""

from __future__ import annotations

import argparse
import re
from pathlib import Path

from ..running import register

_PACKAGE = Path(__file__).resolve().parents[2]


def folder() -> Path:
    """The documents: the package's folder ``docs`` when installed, else the
    checkout's ``docs/``."""
    for candidate in (_PACKAGE / "docs", _PACKAGE.parent / "docs"):
        if any(candidate.glob("*.md")):
            return candidate
    raise FileNotFoundError(f"no docs/*.md next to {_PACKAGE}")


def anchor(heading: str) -> str:
    """The anchor of a Markdown heading as the citations write it (GitHub's rule:
    lower case, punctuation dropped, spaces to hyphens)."""
    text = re.sub(r"[^\w\- ]", "", heading.strip().lower())
    return text.replace(" ", "-")


def sections(text: str) -> list[tuple[int, str, int]]:
    """``(level, anchor, line)`` of each heading of ``text``, outside code blocks."""
    found, fenced = [], False
    for number, line in enumerate(text.splitlines()):
        if line.startswith("```"):
            fenced = not fenced
        match = None if fenced else re.match(r"(#+) (.*)", line)
        if match:
            found.append((len(match[1]), anchor(match[2]), number))
    return found


def section(text: str, name: str) -> str:
    """The section of ``text`` under the heading whose anchor is ``name``, with its
    subsections; KeyError if there is none."""
    lines = text.splitlines()
    heads = sections(text)
    for i, (level, key, start) in enumerate(heads):
        if key == name:
            end = next((line for lv, _, line in heads[i + 1 :] if lv <= level), len(lines))
            return "\n".join(lines[start:end]).rstrip() + "\n"
    raise KeyError(name)


def add(commands, name: str) -> None:
    sub = register(
        commands,
        name,
        run,
        [],
        models=run,  # the documents are every model's
        help="print a document the help texts cite (docs/*.md)",
        description="Print a page of docs/ or one of its sections, as the help texts cite "
        "them (docs/modelling.md#tension, or modelling#tension); without a name, list "
        "the pages and their sections. The pages ship with the package.",
    )
    sub.add_argument(
        "name",
        nargs="?",
        default=None,
        help="a page or a section: docs/PAGE.md#SECTION, PAGE#SECTION or PAGE (PAGE as "
        "reference/json for a page in a folder)",
    )


def run(args: argparse.Namespace) -> int:
    docs = folder()
    # the pages of docs/ and of its folders, by their path: modelling, reference/json
    pages = {
        path.relative_to(docs).with_suffix("").as_posix(): path
        for path in sorted(docs.glob("*.md")) + sorted(docs.glob("*/*.md"))
    }
    if args.name is None:
        print(f"documents in {docs}:")
        for stem, path in pages.items():
            print(f"  {stem}: " + ", ".join(k for _, k, _ in sections(path.read_text())[1:]))
        return 0
    page, _, part = args.name.removeprefix("docs/").partition("#")
    page = page.removesuffix(".md")
    if page not in pages:
        raise ValueError(f"name: no page {page!r} in docs/ (pages: {', '.join(pages)})")
    text = pages[page].read_text()
    if part:
        try:
            text = section(text, part)
        except KeyError:
            keys = ", ".join(k for _, k, _ in sections(text)[1:])
            raise ValueError(f"name: no section {part!r} in {page} (sections: {keys})") from None
    print(text, end="")
    return 0
