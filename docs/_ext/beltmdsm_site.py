"""The site's own Sphinx extension: what it generates from the package at build time.

* ``reference/api.rst``: an autosummary of every name of ``beltmdsm.__all__``, grouped by
  the module that holds it, so that a name added to the public API joins the reference
  without an edit here;
* ``reference/laws.rst``: the laws of the registry and every parameter;
* ``reference/models.rst``: the registered models, their parameters and modes;
* ``reference/generated.rst``: an autosummary of every module of ``generated/`` (what
  ``python -m derive`` writes), each with its functions;
* ``tutorials/notebooks.rst``, and in ``tutorials/notebooks/`` links to
  ``notebooks/*.ipynb`` (and their helper ``_nbutil.py``), which myst-nb renders and,
  where ``nb_execution_mode`` asks, executes in quick mode; the notebooks stay where
  the tests run them;
* links from the pages of ``docs/`` to repository files that are pages of the site
  (the README, VALIDATION.md, generated/PAPER_CHECK.md) point to those pages, so that
  ``docs/*.md`` read the same on a forge, in ``beltmdsm docs`` and in the site.

Everything written here is listed in .gitignore; nothing is written outside ``docs/``.
"""

from __future__ import annotations

import argparse
import importlib
import os
import pkgutil
import re
import shutil
from pathlib import Path

DOCS = Path(__file__).resolve().parents[1]
ROOT = DOCS.parent

#: Where a link of a page of docs/ to a repository file goes in the site.
SITE_PAGES = {
    "../README.md": "index.rst",
    "../VALIDATION.md": "explanation/validation.md",
    "../generated/PAPER_CHECK.md": "reference/paper_check.md",
}


def parser() -> argparse.ArgumentParser:
    """The command line's argparse tree (for sphinx-argparse): ``beltmdsm.cli.tree``'s,
    the derive commands and the runtime commands."""
    from beltmdsm.cli.tree import build_parser

    built = build_parser()
    built.prog = "beltmdsm"
    # sphinx-argparse reads the help texts as reStructuredText
    stack = [built]
    while stack:
        current = stack.pop()
        if current.description:
            current.description = escape_bars_text(current.description)
        for action in current._actions:
            if action.help:
                action.help = escape_bars_text(action.help)
            if isinstance(action, argparse._SubParsersAction):
                stack.extend(action.choices.values())
                for choice in action._choices_actions:
                    choice.help = escape_bars_text(choice.help or "")
    return built


def _write(path: Path, text: str) -> None:
    """Write only a changed file, so that Sphinx rebuilds only what changed."""
    if not path.exists() or path.read_text(encoding="utf-8") != text:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")


def api_page() -> str:
    """``reference/api.rst``: the public names of ``beltmdsm``, a table per module."""
    import beltmdsm

    groups: dict[str, list[str]] = {}
    for name in beltmdsm.__all__:
        module = getattr(beltmdsm, name).__module__
        groups.setdefault(module, []).append(name)
    lines = [
        ".. This page is written by docs/_ext/beltmdsm_site.py from beltmdsm.__all__.",
        "",
        "Python API",
        "==========",
        "",
        ".. currentmodule:: beltmdsm",
        "",
        "Every name below is importable from the package itself (``from beltmdsm import",
        "floquet_band``); the heading names the module that defines it. The pages are",
        "generated from the docstrings.",
        "",
    ]
    for module, names in groups.items():
        title = f"``{module}``"
        lines += [title, "-" * len(title), ""]
        doc = (importlib.import_module(module).__doc__ or "").strip()
        first = doc.split("\n\n")[0].replace("\n", " ") if doc else ""
        if first:
            lines += [first, ""]
        lines += [".. autosummary::", "   :toctree: api", "   :nosignatures:", ""]
        lines += [f"   {name}" for name in names] + [""]
    return "\n".join(lines)


def generated_page() -> str:
    """``reference/generated.rst``: the modules ``python -m derive`` writes."""
    import beltmdsm.generated

    modules = sorted(
        m.name
        for m in pkgutil.iter_modules(beltmdsm.generated.__path__)
        if not m.name.startswith("_") and not m.ispkg
    )
    lines = [
        ".. This page is written by docs/_ext/beltmdsm_site.py from the modules of generated/.",
        "",
        "Generated modules",
        "=================",
        "",
        "``python -m derive`` writes these plain numpy modules from the derivations of",
        "``derive/`` (never edit them by hand; ``python -m derive --check`` fails when they",
        "are stale). Each module of ``beltmdsm.generated`` has an mpmath twin in",
        "``beltmdsm.generated.mp`` with the same functions at arbitrary precision, where the",
        "module lists one.",
        "",
        ".. autosummary::",
        "   :toctree: gen",
        "   :template: autosummary/generated_module.rst",
        "",
    ]
    lines += [f"   beltmdsm.generated.{name}" for name in modules] + [""]
    return "\n".join(lines)


def _rst_text(text: str) -> str:
    """Plain text as reStructuredText inline text (no markup)."""
    return re.sub(r"([\\`*|])", r"\\\1", str(text))


def laws_page() -> str:
    """``reference/laws.rst``: the laws of the registry and every parameter, from
    ``beltmdsm.generated.parameters`` (derive/laws.py wrote it), so that a law joins the page
    when ``python -m derive`` adds it."""
    from beltmdsm.generated.parameters import (
        LAW_PARAMETERS,
        OPTION_DEFAULTS,
        OPTION_DOCS,
        OPTIONS,
        PARAMETERS,
    )

    lines = [
        ".. This page is written by docs/_ext/beltmdsm_site.py from beltmdsm.generated.parameters.",
        "",
        "Laws and parameters",
        "===================",
        "",
        "The laws of the model, one option each for friction, contact and tension, from the",
        "registry ``derive/laws.py`` (:doc:`../extending` adds one). The generated functions",
        "take the options their equations contain as keywords; ``Model`` and every command",
        "take all three (``friction=``, ``--friction``).",
        "",
        ".. list-table::",
        "   :header-rows: 1",
        "   :widths: 12 18 50 20",
        "",
        "   * - option",
        "     - choice",
        "     - law",
        "     - its own parameters",
    ]
    for option, choices in OPTIONS.items():
        for choice in choices:
            default = " (default)" if OPTION_DEFAULTS[option] == choice else ""
            own = ", ".join(f"``{n}``" for n in LAW_PARAMETERS[option, choice]) or "none"
            lines += [
                f"   * - ``{option}=``, ``--{option}``",
                f"     - ``{choice}``{default}",
                f"     - {_rst_text(OPTION_DOCS[option][choice])}",
                f"     - {own}",
            ]
    lines += [
        "",
        "Parameters",
        "----------",
        "",
        "Every parameter, with its unit, the base value of the paper's Fig. 2 set and its",
        "domain (a value outside it is refused, naming the parameter: :doc:`refusals`).",
        "",
        ".. list-table::",
        "   :header-rows: 1",
        "   :widths: 12 10 10 14 54",
        "",
        "   * - name",
        "     - unit",
        "     - base",
        "     - domain",
        "     - meaning",
    ]
    for row in PARAMETERS:
        law = f" (law ``{row['law'][0]}={row['law'][1]}``)" if row.get("law") else ""
        if row["base"] is not None:
            base = f"{row['base']:g}"
        elif row.get("default_from"):
            base = f"``{row['default_from']}``"  # the two-frequency split of one flag
        else:
            base = "none"  # derived (Vhat) unless given
        lines += [
            f"   * - ``{row['name']}``",
            f"     - {_rst_text(row['unit'])}",
            f"     - {base}",
            f"     - {_rst_text(row['domain'])}",
            f"     - {_rst_text(row['description'])}{law}",
        ]
    return "\n".join(lines + [""])


def models_page() -> str:
    """``reference/models.rst``: the registered models, their parameters and what each
    supports, from ``beltmdsm.generated.models`` (derive/models/ wrote it), so that a model
    joins the page when ``python -m derive`` adds it."""
    from beltmdsm.generated.models import MODELS, load
    from beltmdsm.state_names import module_units as state_units

    lines = [
        ".. This page is written by docs/_ext/beltmdsm_site.py from beltmdsm.generated.models.",
        "",
        "Models",
        "======",
        "",
        "The registered models, one entry each in ``derive/models/entries.py``",
        "(:doc:`../howto/own_model` adds one), the default first. Each has a generated",
        "module ``beltmdsm.generated.models.<name>`` with its hybrid system (modes, surfaces,",
        "saltation matrices, mode Jacobians, the derived holding force of stick) and its",
        "steady sliding (equilibrium, characteristic polynomial, Hurwitz determinants),",
        "and an mpmath twin ``beltmdsm.generated.mp.models.<name>`` (the same kernels at",
        "``mpmath.mp.dps`` digits, the tests' reference).",
    ]
    for name in MODELS:
        m = load(name)
        modes = ", ".join(f"``{k}`` ({v})" for k, v in m.MODES.items())
        excitation = ", ".join(
            f"``{x[0]}`` (``{x[1]}``, ``{x[2]}``, ``{x[3]}``)" for x in m.EXCITATION
        )
        absent = ", ".join(f"``{k}``" for k in m.ABSENT) or "none"
        default = " (default)" if name == MODELS[0] else ""
        title = f"``{name}``{default}"
        lines += [
            "",
            title,
            "-" * len(title),
            "",
            _rst_text(m.SUMMARY) + ".",
            "",
            "* states: "
            + ", ".join(f"``{s}`` [{_rst_text(u)}]" for s, u in zip(m.STATES, state_units(m))),
            f"* contact: {'unilateral (flight possible)' if m.UNILATERAL else 'bilateral'}",
            f"* modes: {modes}",
            f"* friction laws: {', '.join(f'``{law}``' for law in m.FRICTION_LAWS)}",
            f"* excitation: {excitation or 'none'}",
            "* equilibrium: "
            + "; ".join(f"``{law}``: {_rst_text(path)}" for law, path in m.EQUILIBRIUM.items()),
            f"* the paper's own pieces absent: {absent}",
            "",
            ".. list-table::",
            "   :header-rows: 1",
            "   :widths: 14 10 10 66",
            "",
            "   * - parameter",
            "     - unit",
            "     - default",
            "     - meaning",
        ]
        for p in m.DEFAULTS:
            lines += [
                f"   * - ``{p}``",
                f"     - {_rst_text(m.UNITS[p])}",
                f"     - {m.DEFAULTS[p]:g}",
                f"     - {_rst_text(m.DESCRIPTIONS[p])}",
            ]
    return "\n".join(lines + [""])


def link_notebooks() -> None:
    """Link ``notebooks/*.ipynb`` and ``_nbutil.py`` into ``tutorials/notebooks/``.

    Links, not copies: executed there, ``_nbutil`` resolves its own path to
    ``notebooks/`` and so finds the repository root and the figures folder as under
    nbmake."""
    target = DOCS / "tutorials" / "notebooks"
    target.mkdir(parents=True, exist_ok=True)
    sources = sorted((ROOT / "notebooks").glob("*.ipynb")) + [ROOT / "notebooks" / "_nbutil.py"]
    wanted = {source.name for source in sources}
    for stale in target.iterdir():
        if stale.name not in wanted and stale.is_symlink():
            stale.unlink()
    for source in sources:
        link = target / source.name
        if link.is_symlink() and Path(os.readlink(link)) == source:
            continue
        if link.is_symlink() or link.exists():
            link.unlink()
        link.symlink_to(source)


def notebook_index() -> str:
    """``tutorials/notebooks.rst``: the paper's figures, one notebook a page."""
    lines = [
        ".. This page is written by docs/_ext/beltmdsm_site.py from notebooks/*.ipynb.",
        "",
        "The paper's figures, redrawn",
        "============================",
        "",
        "One notebook per group of figures of the paper (the files of ``notebooks/``): each",
        "states the paper's claim, draws our figure from the package and ends with a cell",
        "that checks what it claims. The site executes them in quick mode (coarse grids;",
        "``BELTMDSM_FULL=1`` for the paper's resolution, see :doc:`../howto/figures`).",
        "",
        ".. toctree::",
        "   :maxdepth: 1",
        "",
    ]
    lines += [f"   notebooks/{p.stem}" for p in sorted((ROOT / "notebooks").glob("*.ipynb"))]
    return "\n".join(lines + [""])


def generate(app, config=None) -> None:
    """config-inited: write the generated pages and links before Sphinx looks for its
    source files (at builder-inited, a fresh checkout's api.rst would be written after
    the search, and autosummary would find no page to write stubs for). The stubs of
    an earlier build go first: autosummary writes the current ones and removes none, and
    a stub of a module that moved (``generated.tableau`` became
    ``beltmdsm.generated.tableau``) would fail the build."""
    shutil.rmtree(DOCS / "reference" / "gen", ignore_errors=True)
    _write(DOCS / "reference" / "api.rst", api_page())
    _write(DOCS / "reference" / "generated.rst", generated_page())
    _write(DOCS / "reference" / "laws.rst", laws_page())
    _write(DOCS / "reference" / "models.rst", models_page())
    _write(DOCS / "tutorials" / "notebooks.rst", notebook_index())
    link_notebooks()


def relink(app, docname: str, source: list[str]) -> None:
    """source-read: a top-level page's links to repository files that are site pages."""
    if "/" in docname:
        return
    text = source[0]
    for cited, page in SITE_PAGES.items():
        text = re.sub(r"\]\(" + re.escape(cited) + r"(#[\w-]+)?\)", f"]({page}\\1)", text)
    source[0] = text


#: ``|Vr|`` in prose is an absolute value, which reStructuredText would read as a
#: substitution reference; the laws' docs in derive/laws.py reach generated/ and the
#: help texts that way. A bar followed by a space (a table's or line block's) is left.
_BARS = re.compile(r"(?<![\\\w])\|(?=[^\s|])([^|`]*?[^\s|\\])\|(?!\w)")
_LITERAL = re.compile(r"(``.*?``|`[^`\n]*`)", re.S)


def escape_bars_text(text: str) -> str:
    """``text`` with each ``|x|`` outside literals escaped (``\\|x\\|``)."""
    parts = _LITERAL.split(text)
    parts[::2] = [_BARS.sub(r"\\|\1\\|", part) for part in parts[::2]]
    return "".join(parts)


def escape_bars(app, what, name, obj, options, lines: list[str]) -> None:
    """autodoc-process-docstring: absolute values as text, not substitutions."""
    lines[:] = escape_bars_text("\n".join(lines)).split("\n")


def skip_fields(app, what, name, obj, skip, options):
    """autodoc-skip-member: a class's data (a dataclass's fields, with their defaults)
    is in its docstring's Attributes section; methods and properties are members."""
    if what == "class" and not (callable(obj) or isinstance(obj, property)):
        return True
    return None


def _resolve_object(target: str):
    """The object that the dotted path ``target`` names (a module, then attributes);
    LookupError if there is none."""
    parts = target.split(".")
    for cut in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:cut]))
        except ImportError:
            continue
        try:
            for attr in parts[cut:]:
                obj = getattr(obj, attr)
        except AttributeError:
            break
        return obj
    raise LookupError(target)


def public_reference(app, env, node, contnode):
    """missing-reference: a docstring's reference to an object by the path of the module
    that defines it (``beltmdsm.continuation.band.floquet_band``) links to its page under
    the public name (``beltmdsm.floquet_band``); one to an object that exists but has no
    page (a private helper) reads as text. A name that names nothing stays an error."""
    if node.get("refdomain") != "py" or not node.get("reftarget", "").startswith("beltmdsm."):
        return None
    try:
        obj = _resolve_object(node["reftarget"])
    except LookupError:
        return None
    import beltmdsm

    public = next((n for n in beltmdsm.__all__ if getattr(beltmdsm, n) is obj), None)
    if public is not None:
        domain = env.domains["py"]
        found = domain.resolve_xref(
            env, node["refdoc"], app.builder, "obj", f"beltmdsm.{public}", node, contnode
        )
        if found is not None:
            return found
    return contnode


def setup(app):
    app.connect("missing-reference", public_reference)
    app.connect("autodoc-skip-member", skip_fields)
    app.connect("autodoc-process-docstring", escape_bars)
    app.connect("config-inited", generate)
    app.connect("source-read", relink)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
