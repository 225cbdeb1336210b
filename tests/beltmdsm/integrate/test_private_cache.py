"""The caches' folders: one rule for both, private, never shared or shadowing (issue 28).

`beltmdsm.generated._support.cache_root` and `user_cache` (the compiled code and numba's cache),
`beltmdsm.batch.cache.default_cache_dir` (the sweeps).
"""

import os
import stat
import subprocess
import sys
import threading
from pathlib import Path

import pytest

from beltmdsm.batch.cache import default_cache_dir
from beltmdsm.generated import _support

ROOT = Path(__file__).resolve().parents[3]


@pytest.fixture
def env(monkeypatch, tmp_path):
    for name in ("BELTMDSM_CACHE", "XDG_CACHE_HOME", "NUMBA_CACHE_DIR"):
        monkeypatch.delenv(name, raising=False)
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    return monkeypatch


def _mode(path):
    return stat.S_IMODE(os.lstat(path).st_mode)


def test_one_rule_for_the_sweeps_and_the_compiled_code(env, tmp_path):
    # no variable: ~/.cache/beltmdsm-cache
    home = tmp_path / "home" / ".cache" / "beltmdsm-cache"
    assert default_cache_dir() == home / "sweeps"
    assert _support.user_cache("compiled") == str(home / "compiled")
    # an empty BELTMDSM_CACHE counts as unset: not the current folder (issue 28: it
    # wrote the sweep files there)
    env.setenv("BELTMDSM_CACHE", "")
    assert default_cache_dir() == home / "sweeps"
    # XDG_CACHE_HOME is honoured by both (only the compiled code's did)
    env.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert default_cache_dir() == tmp_path / "xdg" / "beltmdsm-cache" / "sweeps"
    assert _support.user_cache("numba") == str(tmp_path / "xdg" / "beltmdsm-cache" / "numba")
    # a relative XDG_CACHE_HOME is invalid (the XDG specification): the default
    env.setenv("XDG_CACHE_HOME", "relative")
    assert default_cache_dir() == home / "sweeps"
    # BELTMDSM_CACHE names the folder of both
    env.setenv("BELTMDSM_CACHE", str(tmp_path / "mine"))
    assert default_cache_dir() == tmp_path / "mine" / "sweeps"
    assert _support.user_cache("compiled") == str(tmp_path / "mine" / "compiled")


def test_the_cache_folder_is_no_package_name(env, tmp_path):
    # issue 28: a folder "beltmdsm" in the current folder is imported as a namespace
    # package in place of the installed one
    name = os.path.basename(_support.cache_root())
    assert name == _support.CACHE_NAME and not name.isidentifier()
    _support.user_cache("compiled")
    made = tmp_path / "home" / ".cache"
    assert [p.name for p in made.iterdir()] == [name]


def test_the_compiled_code_folder_is_private(env, tmp_path):
    folder = Path(_support.user_cache("compiled"))
    assert _mode(folder) == 0o700 and os.lstat(folder).st_uid == os.geteuid()
    # one that others may write is made private (it is ours)
    folder.chmod(0o777)
    assert _support.user_cache("compiled") == str(folder) and _mode(folder) == 0o700


@pytest.mark.skipif(os.geteuid() != 0, reason="giving a folder to another user needs root")
def test_a_folder_of_another_user_is_refused(env, tmp_path):
    env.setenv("BELTMDSM_CACHE", str(tmp_path / "c"))
    (tmp_path / "c" / "compiled").mkdir(parents=True)
    os.chown(tmp_path / "c" / "compiled", 12345, 12345)
    with pytest.raises(OSError, match=r"^no private cache folder .*compiled: it belongs to user"):
        _support.user_cache("compiled")


def test_a_link_or_a_parent_others_may_write_is_refused(env, tmp_path):
    env.setenv("BELTMDSM_CACHE", str(tmp_path / "c"))
    (tmp_path / "c").mkdir()
    (tmp_path / "elsewhere").mkdir()
    (tmp_path / "c" / "compiled").symlink_to(tmp_path / "elsewhere")
    with pytest.raises(OSError, match="compiled: it is not a folder; set BELTMDSM_CACHE"):
        _support.user_cache("compiled")
    # a parent that others may write (and is not sticky, as /tmp is): they could
    # rename the private folder and put their own in its place
    (tmp_path / "c").chmod(0o777)
    with pytest.raises(OSError, match="others may write its parent folder"):
        _support.user_cache("numba")
    (tmp_path / "c").chmod(0o777 | stat.S_ISVTX)
    assert _support.user_cache("numba") == str(tmp_path / "c" / "numba")


def test_concurrent_threads_all_get_the_folder(env, tmp_path):
    # issue 28: the probe was named by the process id only; 8 threads x 50 calls made
    # one fall back to the shared temporary folder
    env.setenv("BELTMDSM_CACHE", str(tmp_path / "c"))
    got, errors = [], []

    def work():
        for _ in range(50):
            try:
                got.append(_support.user_cache("compiled"))
            except OSError as err:
                errors.append(err)

    threads = [threading.Thread(target=work) for _ in range(8)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert errors == [] and set(got) == {str(tmp_path / "c" / "compiled")} and len(got) == 400
    assert list((tmp_path / "c" / "compiled").iterdir()) == []


def _no_home(tmp_path):
    env = {k: v for k, v in os.environ.items() if k not in ("XDG_CACHE_HOME", "NUMBA_CACHE_DIR")}
    env.pop("BELTMDSM_CACHE", None)
    (tmp_path / "tmp").mkdir()
    env.update(HOME="/proc/nonexistent", TMPDIR=str(tmp_path / "tmp"), PYTHONPATH=str(ROOT))
    return env


def test_without_a_home_nothing_goes_to_the_shared_temporary_folder(tmp_path):
    # issue 28: with HOME=/proc/nonexistent every run fell back to /tmp/beltmdsm, a
    # world-writable folder that then shadowed the package for every user
    code = (
        "import warnings, numpy\n"
        "from beltmdsm.generated import _support\n"
        "try:\n"
        "    _support.user_cache('compiled')\n"
        "except OSError as err:\n"
        "    print('refused:', err)\n"
        "with warnings.catch_warnings(record=True) as caught:\n"
        "    warnings.simplefilter('always')\n"
        "    _support.import_numba(False)\n"
        "    _support.import_numba(False)\n"
        "print(len(caught), caught[0].category.__name__, _support.DISK_CACHE)\n"
        "square = _support.compiled(lambda x: x * x, 'float64', 'numba')\n"
        "print(square(numpy.array([3.0]))[0])\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", code],
        env=_no_home(tmp_path),
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert lines[0] == (
        "refused: no private cache folder /proc/nonexistent/.cache/beltmdsm-cache/compiled: "
        "No such file or directory; set BELTMDSM_CACHE to a folder of yours"
    )
    # said once; numba then caches nothing and still compiles
    assert lines[1:] == ["1 CacheFolderWarning False", "9.0"]
    assert list((tmp_path / "tmp").iterdir()) == []
    assert not (tmp_path / "beltmdsm").exists()


@pytest.mark.slow
def test_without_a_home_a_run_says_so_once_and_is_computed(tmp_path):
    # the integrators compiled in memory (about 30 s on 2 busy cores)
    done = subprocess.run(
        [sys.executable, "-m", "beltmdsm", "simulate", "--t-end", "5"],
        env=_no_home(tmp_path),
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr
    said = [line for line in done.stderr.splitlines() if "warning:" in line]
    assert len(said) == 1 and "no private cache folder" in said[0], done.stderr
    assert "energy balance" in done.stdout
    assert list((tmp_path / "tmp").iterdir()) == []
