"""The private folders of what is compiled at run time (numba's cache, the compiled
modules) and of the package's other caches: `cache_root`, `user_cache`.
Reached through `beltmdsm.generated._support`.

Copied verbatim into ``generated/_cache.py`` by ``python -m derive``; edit the
template in ``derive/codegen/templates/`` and regenerate.
"""

import os
import tempfile

#: The folder of the package's caches inside the user's cache folder. Not named like
#: a package: a folder "beltmdsm" in the current directory would be imported as a
#: namespace package in place of the installed one.
CACHE_NAME = "beltmdsm-cache"


def cache_root():
    """The folder of every cache of the package (the sweeps' and the compiled code's).

    ``$BELTMDSM_CACHE`` where set and not empty, else ``$XDG_CACHE_HOME/beltmdsm-cache``
    where that is an absolute path, else ``~/.cache/beltmdsm-cache`` (an empty variable
    counts as unset, as the XDG base directory specification has it). Nothing else:
    no shared temporary folder.
    """
    given = os.environ.get("BELTMDSM_CACHE")
    if given:
        return os.path.abspath(given)
    xdg = os.environ.get("XDG_CACHE_HOME")
    if not (xdg and os.path.isabs(xdg)):
        xdg = os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(xdg, CACHE_NAME)


def user_cache(name):
    """A private folder ``cache_root()/name`` for what is compiled at run time: code
    that is imported, and numba's cache, which it unpickles.

    Outside the package (an installed package's files belong to its installer, and a
    file left in it survives ``pip uninstall``), and private: created with mode 0700,
    then checked to be a folder (not a link) owned by this user that no one else can
    write, in a folder that no one else can rename it in (else another user could
    put code there that this process runs). A test file of a unique name (per
    process and thread) is written and removed.

    Raises
    ------
    OSError
        One line naming the folder and why, when it cannot be made private.
    """
    import stat

    folder = os.path.join(cache_root(), name)
    try:
        os.makedirs(folder, mode=0o700, exist_ok=True)
        info = os.lstat(folder)
        if not stat.S_ISDIR(info.st_mode):
            raise OSError("it is not a folder")
        if hasattr(os, "geteuid"):
            if info.st_uid != os.geteuid():
                raise OSError(f"it belongs to user id {info.st_uid}, not to this one")
            if info.st_mode & 0o077:
                os.chmod(folder, 0o700)
            parent = os.stat(os.path.dirname(folder))
            if parent.st_mode & 0o022 and not parent.st_mode & stat.S_ISVTX:
                raise OSError("others may write its parent folder, and rename it")
        fd, probe = tempfile.mkstemp(dir=folder, prefix=".probe-")
        os.close(fd)
        os.remove(probe)
    except OSError as err:
        raise OSError(
            f"no private cache folder {folder}: {err.strerror or err}; set BELTMDSM_CACHE "
            "to a folder of yours"
        ) from None
    return folder


class CacheFolderWarning(UserWarning):
    """No private cache folder: what is compiled is not kept between runs."""
