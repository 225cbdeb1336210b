"""Where ``beltmdsm.generated`` and ``beltmdsm.derive`` are: inside the package, or beside it.

The wheel installs generated/ and derive/ inside the package (pyproject.toml's
``[tool.setuptools.package-dir]``), so that a user's own ``generated/`` or
``derive.py`` cannot shadow them. A source checkout keeps them at its top level,
beside beltmdsm/ (the project's layout): there `map_siblings` installs a finder that
maps the two names, and only them, to those folders. It is the finder of the
beltmdsm that was imported, not setuptools' editable one: that one maps to the
checkout that was installed, which need not be the one on ``sys.path`` (a second
worktree, or a copy in a test's temporary folder).

Their submodules (``beltmdsm.generated.mp.stability``) are then found the usual way,
through the package's ``__path__``. Imported by their old top-level names, both
packages refuse in one line (their ``__init__``): a second name would load a second
copy of every module, and of the law registry.
"""

from __future__ import annotations

import importlib.util
import sys
from importlib.abc import MetaPathFinder
from pathlib import Path

__all__ = ["SIBLINGS", "map_siblings"]

#: The packages a checkout keeps beside beltmdsm/ and the wheel installs inside it.
SIBLINGS = ("generated", "derive")


class _Siblings(MetaPathFinder):
    """Finds ``beltmdsm.<name>`` in a checkout's ``<root>/<name>/`` for the names given."""

    def __init__(self, folders: dict[str, Path]):
        self.folders = folders

    def find_spec(self, fullname, path=None, target=None):
        folder = self.folders.get(fullname)
        if folder is None:
            return None
        return importlib.util.spec_from_file_location(
            fullname, folder / "__init__.py", submodule_search_locations=[str(folder)]
        )


def map_siblings(package: str, here: str) -> None:
    """In a source checkout, map ``<package>.generated`` and ``<package>.derive`` to the
    folders beside ``here`` (the package's folder); installed, do nothing.

    The path is taken as imported, not resolved: a checkout whose beltmdsm/ is a link
    (a test's copy of derive/ beside a link to beltmdsm/) maps its own folders.
    """
    root = Path(here).parent
    folders = {
        f"{package}.{name}": root / name
        for name in SIBLINGS
        if not (Path(here) / name).is_dir() and (root / name / "__init__.py").is_file()
    }
    if folders:
        sys.meta_path.insert(0, _Siblings(folders))
