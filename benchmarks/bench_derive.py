"""CPU time and peak memory of ``python -m derive``, per added friction law (issue 41, item 7).

Each derivation runs in a copy of a checkout (its derive/ copied, beltmdsm/ linked)
with laws appended to its derive/laws.py, as docs/extending.md says to add them
(those of tests/derive/test_added_laws.py: the cubic law, the rational-root law, and
all three with the docs' worked example), and ``python -m derive --out DIR`` writes a
complete generated/ there (the budgeted decisions start from the checkout's own
generated/_budget.py, as a user's first derivation of a new law does). Both ways, in
the same run:

* **ours**: this checkout's derive/;
* **baseline**: derive/ of the commit ``--baseline`` (default `BASELINE`, main before
  item 7's work), extracted with ``git archive``.

CPU time is the derivation's and its budget workers' (``RUSAGE_CHILDREN`` of a wrapper
process around it), not wall time: the machine is shared. Peak memory is the largest
resident set of the derivation or a worker. The generated files of both are compared:
"identical", or the files that differ (an added law whose futile step is now skipped
words its refusal differently). The load average is printed with each row.

Run from the repository root: ``python -m benchmarks.bench_derive [--laws shipped,cubic]
[--jobs 2]`` (minutes per row: each derivation takes about a minute of CPU).
"""

from __future__ import annotations

import argparse
import concurrent.futures
import filecmp
import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: main before issue 41 item 7 (the derivation this benchmark compares against).
BASELINE = "8877ea6"

#: Runs ``python -m derive --out DIR`` in a checkout and prints its children's rusage.
_WRAPPER = """
import json, resource, subprocess, sys
done = subprocess.run([sys.executable, "-m", "derive", "--out", sys.argv[1]],
                      capture_output=True, text=True)
u = resource.getrusage(resource.RUSAGE_CHILDREN)
print(json.dumps({"rc": done.returncode, "cpu": u.ru_utime + u.ru_stime,
                  "maxrss_mb": u.ru_maxrss / 1024, "err": done.stderr[-2000:]}))
"""


def _laws() -> dict[str, str]:
    """The law sets: name -> text appended to derive/laws.py."""
    sys.path[:0] = [str(ROOT / "tests"), str(ROOT / "tests" / "derive")]
    import test_added_laws as added

    marker = 'register(\n    "friction",\n    FrictionLaw(\n        "rational_sqrt"'
    cubic, rest = added.ISSUE_LAWS.split(marker)
    rational = marker + rest
    return {
        "shipped": "",
        "cubic": cubic,
        "rational_sqrt": rational,
        "all three": added._docs_example() + added.ISSUE_LAWS,
    }


def _checkout(source: Path, folder: Path, laws: str) -> Path:
    shutil.copytree(source / "derive", folder / "derive")
    with open(folder / "derive" / "laws.py", "a") as fh:
        fh.write("\n" + laws)
    (folder / "beltmdsm").symlink_to(ROOT / "beltmdsm", target_is_directory=True)
    return folder


def _derive(folder: Path) -> dict:
    env = {**os.environ, "PYTHONPATH": str(folder), "PYTHONDONTWRITEBYTECODE": "1"}
    env.pop("BELTMDSM_DERIVE_LOG", None)
    out = subprocess.run(
        [sys.executable, "-c", _WRAPPER, str(folder / "generated")],
        cwd=folder, env=env, capture_output=True, text=True, check=True,
    )  # fmt: skip
    result = json.loads(out.stdout)
    result["load"] = os.getloadavg()[0]
    return result


def _differing(a: Path, b: Path) -> list[str]:
    """Files of generated/ that differ between two derivations (relative paths)."""
    found = []
    for path in sorted(a.rglob("*.py")):
        rel = path.relative_to(a)
        if not (b / rel).is_file() or not filecmp.cmp(path, b / rel, shallow=False):
            found.append(str(rel))
    return found


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--baseline", default=BASELINE, help="commit of the baseline derive/")
    parser.add_argument("--laws", default="shipped,cubic,rational_sqrt,all three")
    parser.add_argument("--jobs", type=int, default=1, help="derivations run at once")
    args = parser.parse_args(argv)
    sets = _laws()
    chosen = [name.strip() for name in args.laws.split(",")]
    unknown = set(chosen) - set(sets)
    if unknown:
        parser.error(f"--laws: unknown {sorted(unknown)}; choose from {sorted(sets)}")
    with tempfile.TemporaryDirectory(prefix="bench_derive_") as tmp:
        tmp = Path(tmp)
        base = tmp / "baseline"
        base.mkdir()
        archive = subprocess.run(
            ["git", "archive", args.baseline, "derive"], cwd=ROOT, capture_output=True,
            check=True,
        )  # fmt: skip
        subprocess.run(["tar", "-x", "-C", str(base)], input=archive.stdout, check=True)
        jobs = {}
        for name in chosen:
            for way, source in (("baseline", base), ("ours", ROOT)):
                folder = tmp / f"{way}-{name.replace(' ', '_')}"
                jobs[(name, way)] = _checkout(source, folder, sets[name])
        with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
            results = dict(zip(jobs, pool.map(_derive, jobs.values())))
        print(f"python -m derive, CPU time [s] and peak memory [MB]; baseline {args.baseline}")
        print(f"{'laws':<14} {'baseline':>16} {'ours':>16} {'ratio':>6} {'load':>5}  generated/")
        shipped = {}
        for name in chosen:
            b, o = results[(name, "baseline")], results[(name, "ours")]
            for r in (b, o):
                if r["rc"] != 0:
                    print(f"{name}: derivation failed:\n{r['err']}")
            if name == "shipped":
                shipped = {"baseline": b["cpu"], "ours": o["cpu"]}
            differ = _differing(
                jobs[(name, "baseline")] / "generated", jobs[(name, "ours")] / "generated"
            )
            print(
                f"{name:<14} {b['cpu']:7.1f} s {b['maxrss_mb']:5.0f} MB "
                f"{o['cpu']:7.1f} s {o['maxrss_mb']:5.0f} MB {o['cpu'] / b['cpu']:6.2f} "
                f"{(b['load'] + o['load']) / 2:5.1f}  "
                + ("identical" if not differ else "differ: " + ", ".join(differ))
            )
        if shipped:
            print("added cost over the shipped laws [s CPU] (baseline -> ours):")
            for name in chosen:
                if name != "shipped":
                    b, o = results[(name, "baseline")]["cpu"], results[(name, "ours")]["cpu"]
                    print(
                        f"  {name:<14} {b - shipped['baseline']:6.1f} -> {o - shipped['ours']:6.1f}"
                    )


if __name__ == "__main__":
    main()
