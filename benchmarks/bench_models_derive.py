"""CPU time and peak memory of one model's derivation, per registered model (issue 39).

Issue 39 bounds the derivation of one model at 2 minutes of CPU time and 2 GB. Each row
derives one model in a fresh process: the model's equations, hybrid system and steady
sliding by SymPy (derive/models/), then its generated module(s) as text, the way
``python -m derive`` writes them. Both ways, in the same run:

* **ours**: this checkout's derive/: generated/models/<name>.py and its mpmath twin
  generated/mp/models/<name>.py;
* **baseline**: derive/ of the commit ``--baseline`` (default `BASELINE`, main before
  the twins), extracted with ``git archive``: generated/models/<name>.py alone.

CPU time is the process's (user + system), not wall time: the machine is shared. Peak
memory is its largest resident set. Run from the repository root:
``python -m benchmarks.bench_models_derive [--baseline REV]``.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tarfile
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: main before the mpmath twins of the model modules.
BASELINE = "d21985f"

#: Derives one model in a fresh process and prints its CPU time and peak memory.
_ONE = """
import inspect, json, resource, sys, time
name = sys.argv[1]
t0 = time.process_time()
from beltmdsm.derive.models import render
texts = [render.render_model(name)]
if "mp" in inspect.signature(render.render_model).parameters:
    texts.append(render.render_model(name, mp=True))
u = resource.getrusage(resource.RUSAGE_SELF)
print(json.dumps({"cpu": time.process_time() - t0, "maxrss_mb": u.ru_maxrss / 1024,
                  "modules": len(texts), "chars": sum(map(len, texts))}))
"""


def _checkout(rev: str, folder: Path) -> Path:
    """derive/ of ``rev`` beside this checkout's beltmdsm/ and generated/."""
    archive = folder / "derive.tar"
    with open(archive, "wb") as fh:
        subprocess.run(["git", "archive", rev, "derive"], cwd=ROOT, stdout=fh, check=True)
    with tarfile.open(archive) as tar:
        tar.extractall(folder, filter="data")
    for name in ("beltmdsm", "generated"):
        (folder / name).symlink_to(ROOT / name, target_is_directory=True)
    return folder


def _derive(folder: Path, name: str) -> dict:
    env = {**os.environ, "PYTHONPATH": str(folder), "PYTHONDONTWRITEBYTECODE": "1"}
    out = subprocess.run(
        [sys.executable, "-c", _ONE, name],
        cwd=folder,
        env=env,
        capture_output=True,
        text=True,
        check=True,
    )
    return json.loads(out.stdout)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--baseline", default=BASELINE)
    args = parser.parse_args(argv)
    sys.path.insert(0, str(ROOT))
    from beltmdsm.generated.models import MODELS

    print(f"load average {os.getloadavg()[0]:.1f}")
    print(f"{'model':10s} {'way':9s} {'modules':>7s} {'CPU s':>7s} {'peak MB':>8s}")
    with tempfile.TemporaryDirectory() as tmp:
        base = _checkout(args.baseline, Path(tmp))
        for name in MODELS:
            for way, folder in (("ours", ROOT), ("baseline", base)):
                r = _derive(folder, name)
                print(
                    f"{name:10s} {way:9s} {r['modules']:7d} {r['cpu']:7.1f} {r['maxrss_mb']:8.0f}"
                )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
