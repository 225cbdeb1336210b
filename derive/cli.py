"""Command line: ``python -m derive [--check]``, ``python -m derive check-paper``,
``python -m derive simulate|sweep ...``.

Thin: it calls the derivation pipeline (`derive.modules`), the code generator
(`derive.codegen`) and prints what happened. The simulation commands belong to the
runtime layer (`runtime.cli`, `runtime.predict`), which never imports SymPy; they are dispatched
before anything symbolic is imported.
"""
from __future__ import annotations

import argparse
import sys
import time

__all__ = ["main"]

RUNTIME_COMMANDS = ("simulate", "sweep")


def _generate(args) -> int:
    from . import codegen, modules

    start = time.perf_counter()
    mods = modules.all_modules()
    files = codegen.render_all(mods)
    elapsed = time.perf_counter() - start
    if args.check:
        stale = codegen.stale(files)
        if stale:
            for rel, diff in stale.items():
                print(f"STALE generated/{rel}: {diff if len(diff) < 80 else ''}".rstrip())
                if len(diff) >= 80:
                    print(diff)
            print(f"{len(stale)} generated file(s) differ from the derivations; "
                  "run `python -m derive` to regenerate.", file=sys.stderr)
            return 1
        print(f"generated/ is up to date ({len(files)} files, derived in {elapsed:.1f} s).")
        return 0
    changed = codegen.write(files)
    for m in mods:
        names = ", ".join(f.name for f in m.functions)
        print(f"generated/{m.name}.py (+ mp/{m.name}.py): {names}")
    print(f"derived {sum(len(m.functions) for m in mods)} functions in {len(mods)} modules "
          f"in {elapsed:.1f} s; wrote {len(changed)} changed file(s) of {len(files)}.")
    return 0


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv and argv[0] in RUNTIME_COMMANDS:
        from runtime.cli import main as runtime_main
        return runtime_main(argv)
    if argv and argv[0] == "predict":
        from runtime.predict import main as predict_main
        return predict_main(argv)
    if argv and argv[0] == "validate":
        from runtime.validation import main as validate_main
        return validate_main(argv)
    if argv and argv[0] == "check-paper":
        from .paper_check import main as check_paper
        return check_paper(argv[1:])
    parser = argparse.ArgumentParser(
        prog="python -m derive",
        description="Derive the model symbolically and regenerate generated/.")
    parser.add_argument("--check", action="store_true",
                        help="do not write; exit 1 and name the stale files if "
                             "generated/ differs from the derivations")
    args = parser.parse_args(argv)
    return _generate(args)
