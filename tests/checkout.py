"""A source checkout in a temporary folder, for the tests that derive into one.

The package imports generated/ and derive/ as ``beltmdsm.generated`` and
``beltmdsm.derive`` from beside its own folder (beltmdsm/_layout.py), never by a
top-level name from ``sys.path``: a folder with a link to this checkout's beltmdsm/
is a checkout of its own, whose generated/ (written by the test) and derive/ (a copy
the test edits, or a link) are the ones imported when the folder comes first on
``sys.path`` (the working folder of ``python -m``, or ``sys.path.insert(0, folder)``).
"""

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def as_checkout(folder: Path) -> Path:
    """Link this checkout's beltmdsm/ and derive/ into ``folder`` where it has none of
    its own; never generated/, which a test writes (through a link it would rewrite
    this checkout's)."""
    for name in ("beltmdsm", "derive"):
        if not (folder / name).exists():
            (folder / name).symlink_to(ROOT / name, target_is_directory=True)
    return folder
