"""What the README and the docs state about the package, against the code (issue 37
items 1 and 5): the cache folder they name, the dependencies the README's install
gives, the figures of time they quote."""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_the_dask_page_names_the_cache_folder_the_code_uses(monkeypatch, tmp_path):
    from beltmdsm.studies.cache import default_cache_dir

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
