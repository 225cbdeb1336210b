"""The documentation site (docs/, issue 32): it builds, its links resolve, a browser shows it.

* The site builds with warnings as errors and nitpicky references (``-W -n``): a broken
  cross-reference, a docstring that is not valid reStructuredText, a page missing from
  the tables of contents or an example cell that raises fails the build. The pages that
  are notebooks of their own (the first hour, the JSON keys) run at every build; the
  paper's notebooks are not run here (``BELTMDSM_DOCS_EXECUTE=off``), since nbmake runs
  them in the same test run.
* Every internal link of every built page reaches a file of the site, and its
  ``#anchor`` an element of that page (Sphinx's ``linkcheck`` checks only external ones).
* Headless Chromium (Debian's ``chromium``; ``.ci/run`` installs it) renders the start
  page, the API page of ``floquet_band`` and the first-hour tutorial with its figures,
  and the site's search finds ``floquet_band``.
"""

from __future__ import annotations

import html.parser
import importlib.util
import os
import re
import shutil
import struct
import subprocess
import sys
from pathlib import Path
from urllib.parse import unquote, urlsplit

import pytest

ROOT = Path(__file__).resolve().parents[1]
TOOLS = ("sphinx", "numpydoc", "myst_nb", "sphinxarg", "pydata_sphinx_theme")


def start_build(out: Path, execute: str):
    """Start building the site from docs/ into ``out`` (notebooks: ``nb_execution_mode``
    ``execute``, in quick mode): the process and the file of its stderr."""
    env = {**os.environ, "BELTMDSM_DOCS_EXECUTE": execute, "PYTHONPATH": str(ROOT)}
    env.pop("BELTMDSM_FULL", None)
    out.mkdir(parents=True, exist_ok=True)
    err = open(out / "sphinx.err", "w+")
    proc = subprocess.Popen(
        [sys.executable, "-m", "sphinx", "-W", "-n", "--keep-going", "-q", "-b", "html"]
        + ["-D", f"nb_execution_cache_path={out / 'jupyter_cache'}", "docs", str(out / "html")],
        cwd=ROOT,
        stdout=subprocess.DEVNULL,
        stderr=err,
        text=True,
        env=env,
    )
    return proc, err


def finish_build(started, out: Path) -> Path:
    """Wait for `start_build`'s process; the folder of the site's HTML."""
    proc, err = started
    try:
        proc.wait(timeout=900)
    finally:
        stop_site((started, out))
    err.seek(0)
    stderr = err.read()
    err.close()
    assert proc.returncode == 0, f"the site does not build:\n{stderr[-6000:]}"
    return out / "html"


def build(out: Path, execute: str) -> Path:
    """Build the site from docs/ into ``out`` (notebooks: ``nb_execution_mode``
    ``execute``, in quick mode); the folder of its HTML."""
    for tool in TOOLS:
        pytest.importorskip(tool, reason=f"{tool} is not installed (pip install -e '.[docs]')")
    return finish_build(start_build(out, execute), out)


#: The build of `site` started when the session began, if it did (tests/conftest.py,
#: when a test that reads `site` is selected).
STARTED = {}


def start_site(folder: Path):
    """Start `site`'s build into ``folder`` (none where a tool is missing: `site` then
    skips): two minutes of Sphinx in a process of its own, which tests/conftest.py
    starts when the session's tests are collected, so that on a machine of two cores it
    runs beside the rest of the suite."""
    if any(importlib.util.find_spec(tool) is None for tool in TOOLS):
        return None
    return start_build(folder, "off"), folder


def stop_site(started):
    """Kill `start_site`'s build if it still runs."""
    (proc, _), _ = started
    if proc.poll() is None:
        proc.kill()
        proc.wait()


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    """The site built without running the paper's notebooks; its HTML folder."""
    started = STARTED.pop("site", None)
    if started is None:
        return build(tmp_path_factory.mktemp("site"), "off")
    return finish_build(*started)


class _Links(html.parser.HTMLParser):
    """The ``href``/``src`` values and the ``id``s of one HTML page."""

    def __init__(self):
        super().__init__()
        self.links: list[str] = []
        self.ids: set[str] = set()

    def handle_starttag(self, tag, attrs):
        for name, value in attrs:
            if name == "id" and value:
                self.ids.add(value)
            elif name in ("href", "src") and value and tag in ("a", "img", "link", "script"):
                self.links.append(value)


def _parse(page: Path) -> _Links:
    parsed = _Links()
    parsed.feed(page.read_text(encoding="utf-8"))
    return parsed


def broken_links(site: Path) -> list[str]:
    """``page: link`` for every internal link of the built site whose file or anchor is
    missing."""
    # _static holds the theme's templates (webpack-macros.html), not pages
    pages = {p: _parse(p) for p in site.rglob("*.html") if "_static" not in p.parts}
    broken = []
    for page, parsed in pages.items():
        for link in parsed.links:
            parts = urlsplit(link)
            if parts.scheme or parts.netloc or link.startswith(("mailto:", "javascript:")):
                continue  # external: not this test's
            target = (page.parent / unquote(parts.path)).resolve() if parts.path else page
            if target.is_dir():
                target = target / "index.html"
            where = f"{page.relative_to(site)}: {link}"
            if not target.is_file():
                broken.append(where)
            elif parts.fragment and target.suffix == ".html":
                ids = pages[target].ids if target in pages else _parse(target).ids
                if unquote(parts.fragment) not in ids:
                    broken.append(where + " (no such anchor)")
    return sorted(broken)


def test_broken_links_are_found(tmp_path):
    (tmp_path / "sub").mkdir()
    (tmp_path / "index.html").write_text(
        '<a href="sub/page.html#here">ok</a> <a href="sub/page.html#gone">anchor</a>'
        ' <a href="missing.html">file</a> <img src="sub/fig.png"> <a href="https://x.org">x</a>'
    )
    (tmp_path / "sub" / "page.html").write_text(
        '<h1 id="here">t</h1><a href="../index.html">up</a>'
    )
    assert broken_links(tmp_path) == [
        "index.html: missing.html",
        "index.html: sub/fig.png",
        "index.html: sub/page.html#gone (no such anchor)",
    ]


def test_a_reference_by_the_defining_module_is_resolved_or_refused():
    """The site's rule for a docstring's reference to ``beltmdsm.continuation.band.floquet_band``:
    the object is found and links to its public page; a path that names nothing is not
    found, so the build's -n reports it."""
    import beltmdsm

    sys.path.insert(0, str(ROOT / "docs" / "_ext"))
    try:
        from beltmdsm_site import _resolve_object
    finally:
        sys.path.remove(str(ROOT / "docs" / "_ext"))
    assert _resolve_object("beltmdsm.continuation.band.floquet_band") is beltmdsm.floquet_band
    with pytest.raises(LookupError):
        _resolve_object("beltmdsm.continuation.band.no_such_function")


def test_the_site_builds_and_its_internal_links_resolve(site):
    for page in (
        "index.html",
        "reference/api/beltmdsm.floquet_band.html",
        "reference/commands.html",
        "reference/gen/beltmdsm.generated.stability.html",
        "reference/json.html",
        "tutorials/first_hour.html",
        "modelling.html",
    ):
        assert (site / page).is_file(), page
    assert broken_links(site) == []


def test_the_reference_covers_the_public_api_and_the_command_line(site):
    import argparse

    import beltmdsm
    from beltmdsm.cli.tree import build_parser

    for name in beltmdsm.__all__:
        assert (site / "reference" / "api" / f"beltmdsm.{name}.html").is_file(), name
    page = (site / "reference" / "commands.html").read_text(encoding="utf-8")
    commands = {f for kbd in re.findall(r"<kbd>([^<]*)</kbd>", page) for f in kbd.split(", ")}
    parser = build_parser()
    (sub,) = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    for command, subparser in sub.choices.items():
        assert f'id="beltmdsm-{command}"' in page, command
        for action in subparser._actions:
            if isinstance(action, argparse._HelpAction):
                continue  # sphinx-argparse leaves -h out
            for flag in action.option_strings:
                assert flag in commands, f"{command} {flag}"


def test_the_laws_page_is_the_registry(site):
    """Every law of ``beltmdsm.generated.parameters`` with its summary and own parameters, and
    every parameter, on the page of laws (the README's table of laws, moved here)."""
    import html as html_module

    from beltmdsm.generated.parameters import LAW_PARAMETERS, OPTION_DOCS, OPTIONS, PARAMETERS

    page = (site / "reference" / "laws.html").read_text(encoding="utf-8")
    rows = [
        " ".join(html_module.unescape(re.sub(r"<[^>]+>", " ", row)).split())
        for row in re.findall(r"<tr[^>]*>(.*?)</tr>", page, flags=re.S)
    ]
    for option, choices in OPTIONS.items():
        for choice in choices:
            own = LAW_PARAMETERS[option, choice] or ("none",)
            summary = " ".join(OPTION_DOCS[option][choice].split())
            assert any(
                row.startswith(f"{option}= , --{option} {choice}")
                and summary in row
                and all(f" {name}" in row.rsplit(summary, 1)[1] for name in own)
                for row in rows
            ), (option, choice)
    for parameter in PARAMETERS:
        assert any(row.startswith(parameter["name"] + " ") for row in rows), parameter["name"]


def test_the_narrowed_examples_show_what_the_wide_ranges_showed(site):
    """The first hour's coexistence runs over Vb 3..8 (0.5..12 before), json.md's branch
    over 3..5 (2..9 before) and paper_figure.md's predict on 100 points (400), to cut
    the site's build: the first hour still prints both ranges of coexistence that
    tests/beltmdsm/multistability/test_coexistence.py pins over 0.5..12, the branch's
    JSON still has special points to list the keys of, and the prediction's ranges are
    those of the default grid."""
    import html as html_module

    def text(page):
        raw = (site / page).read_text(encoding="utf-8")
        return html_module.unescape(re.sub(r"<[^>]+>", "", raw))

    first = text("tutorials/first_hour.html")
    assert "[3.8699, 4.0576]: 4T, T#1 (grazing to neimark_sacker)" in first
    assert "[6.4154, 7.6738]: 4T, T#2 (grazing to fold)" in first
    json_page = text("reference/json.html")
    branch = json_page[json_page.index("$ beltmdsm branch") :]
    assert "special_points (list of objects): {kind, value, accuracy" in branch
    figure = text("howto/paper_figure.html")
    assert "paper's analysis (tangential V_hat): [[0.0, 8.521]]" in figure
    assert "consistent MDSM: [[4.682, 6.375]]" in figure


def test_the_search_index_holds_floquet_band(site):
    index = (site / "searchindex.js").read_text(encoding="utf-8")
    assert "floquet_band" in index


#: The README's draft (the lead moves it to README.md; then point this at README.md).
README = ROOT / "README.md"


def test_the_readme_example_prints_what_the_readme_says(tmp_path):
    """The README's Python example runs, prints the lines the README shows after it, and
    writes its figure."""
    pytest.importorskip("matplotlib")
    text = README.read_text(encoding="utf-8")
    (code,) = re.findall(r"^```python\n(.*?)^```", text, flags=re.M | re.S)
    (printed,) = re.findall(r"^prints\n\n```\n(.*?)^```", text, flags=re.M | re.S)
    env = {**os.environ, "MPLBACKEND": "Agg", "PYTHONPATH": str(ROOT)}
    done = subprocess.run(
        [sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, env=env
    )
    assert done.returncode == 0, done.stderr[-3000:]
    assert done.stdout == printed
    assert min(_png_size(tmp_path / "band_branch.png")) > 100


def _png_size(path: Path) -> tuple[int, int]:
    data = path.read_bytes()[:24]
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path
    return struct.unpack(">II", data[16:24])


def _chromium() -> str:
    for name in ("chromium", "chromium-browser", "google-chrome"):
        if path := shutil.which(name):
            return path
    pytest.skip("no headless Chromium: install Debian's package `chromium` (.ci/run does)")


def _dom(browser: str, url: str, wait_ms: int = 3000) -> str:
    """The DOM of ``url`` after the page's scripts ran for ``wait_ms`` of virtual time."""
    done = subprocess.run(
        [browser, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run"]
        + [f"--virtual-time-budget={wait_ms}", "--dump-dom", url],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    return done.stdout


def test_a_browser_renders_the_pages_and_the_search_finds_floquet_band(site):
    browser = _chromium()
    start = _dom(browser, (site / "index.html").as_uri())
    assert "Tutorials" in start and "Reference" in start and "bd-header" in start

    api = _dom(browser, (site / "reference/api/beltmdsm.floquet_band.html").as_uri())
    assert 'id="beltmdsm.floquet_band"' in api and "Parameters" in api

    tutorial_page = site / "tutorials" / "first_hour.html"
    tutorial = _dom(browser, tutorial_page.as_uri())
    parsed = _Links()
    parsed.feed(tutorial)
    figures = [src for src in parsed.links if src.endswith(".png")]
    assert len(figures) >= 3, "the first hour draws a run, a branch and a map"
    for src in figures:
        width, height = _png_size((tutorial_page.parent / unquote(src)).resolve())
        assert width > 100 and height > 100, src
    assert "neimark_sacker" in tutorial  # an output of its band cell

    found = _dom(browser, (site / "search.html").as_uri() + "?q=floquet_band", 10000)
    results = found[found.find('id="search-results"') :]
    assert "beltmdsm.floquet_band" in results, "the search did not list floquet_band"


@pytest.mark.slow
def test_every_notebook_renders_with_its_figures(tmp_path):
    """The site as its one command builds it, every notebook run (quick mode; about 3
    minutes on a free core of the 2-core machine): each notebook's page shows a figure
    and no error."""
    built = build(tmp_path, "force")
    notebooks = sorted((ROOT / "notebooks").glob("*.ipynb"))
    assert notebooks
    for notebook in notebooks:
        page = (built / "tutorials" / "notebooks" / f"{notebook.stem}.html").read_text()
        assert "<img" in page and ".png" in page, notebook.name
        assert "Traceback" not in page, notebook.name


def test_the_site_reads_offline_its_math_drawn_at_build(site):
    """Issue 37 item 4: no page loads a script from the network (MathJax's CDN was one),
    and the notebooks' formulas are drawn into the page (docs/_ext/mathtext_math.py)."""
    remote = [
        (page.relative_to(site).as_posix(), link)
        for page in site.rglob("*.html")
        for link in _parse(page).links
        if link.startswith(("http:", "https:", "//")) and link.endswith(".js")
    ]
    assert remote == []
    page = (site / "tutorials" / "notebooks" / "fig05_floquet.html").read_text(encoding="utf-8")
    # MathJax's renderer leaves the TeX in the page, \(V_b\), for its script to draw
    assert '<span class="math" title="V_b"><svg' in page and "\\(V_b\\)" not in page
