"""The derive commands: regenerate (or check) generated/, and the paper check.

The command line is `beltmdsm.cli`'s, one argparse tree (beltmdsm/cli/tree.py): its
top runs `generate` (``beltmdsm [--check] [--out DIR]``, also ``python -m derive``
from a source checkout) and its ``check-paper`` command `check_paper`. derive/
builds no parser and imports no runtime module: the command line imports this
module, never the other way round. Nothing symbolic is imported until a command
runs, so the runtime commands never load SymPy.

The regeneration prints one line per module on stderr as it derives it, with its time
(stdout keeps the summary). A law that `beltmdsm.derive.laws.register` refuses
(`beltmdsm.derive.lawcheck.UnsupportedLaw`), or a model entry that
`beltmdsm.derive.models.register` refuses (`UnsupportedModel`), is one line too, exit
status 2.

Each command takes the parsed arguments (``args.parser`` is the parser that read
them: a refusal is ``args.parser.error(...)``, one line and exit status 2) and
returns the exit status.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

__all__ = ["generate", "check_paper"]


def _progress(spec, seconds):
    """One line on stderr per derived module, as the derivation goes (stdout keeps the
    summary that scripts read)."""
    print(f"derived generated/{spec.name}.py in {seconds:.1f} s", file=sys.stderr, flush=True)


def generate(args) -> int:
    """Derive every module and write generated/ (``args.out``: a complete copy in that
    folder instead), or with ``args.check`` compare it: 1 and the stale files named
    where it differs.

    Refused (``args.parser.error``): writing the package's own generated/ outside a
    source checkout (an installed package is not rewritten; ``--out DIR`` writes
    elsewhere), a law or a model entry that `register` refuses.
    """
    try:
        from . import budget, codegen, modules
        from .models import render as models_render
    except ValueError as err:  # a law or a model refused at `register`
        if type(err).__name__ not in ("UnsupportedLaw", "UnsupportedModel"):
            raise
        args.parser.exit(2, f"{args.parser.prog}: error: {err}\n")

    root = codegen.GENERATED if args.out is None else Path(args.out)
    if args.out is None and not args.check and not codegen.source_checkout():
        args.parser.error(
            f"regenerating generated/ needs a source checkout: this one is installed "
            f"({codegen.GENERATED.parent}); give --out DIR to write a complete copy there"
        )
    # the budgeted decisions recorded with generated/ (beltmdsm.derive.budget): a copy
    # written elsewhere starts from the package's own record
    recorded = root / budget.RECORD
    budget.use_record(recorded if recorded.is_file() else codegen.GENERATED / budget.RECORD)
    start = time.perf_counter()
    mods = modules.all_modules(progress=_progress)
    files = codegen.render_all(mods)
    files.update(models_render.files())  # generated/models/ (issue 39)
    files[budget.RECORD] = budget.render_record(codegen.HEADER)
    elapsed = time.perf_counter() - start
    if args.check:
        stale = codegen.stale(files, root)
        if stale:
            for rel, diff in stale.items():
                print(f"STALE generated/{rel}: {diff if len(diff) < 80 else ''}".rstrip())
                if len(diff) >= 80:
                    print(diff)
            print(
                f"{len(stale)} generated file(s) differ from the derivations; "
                "run `python -m derive` to regenerate.",
                file=sys.stderr,
            )
            return 1
        print(f"generated/ is up to date ({len(files)} files, derived in {elapsed:.1f} s).")
        return 0
    changed = codegen.write(files, root)
    for m in mods:
        names = ", ".join([f.name for f in m.functions] + [c[0] for c in m.constants])
        print(f"generated/{m.name}.py{f' (+ mp/{m.name}.py)' if m.mp else ''}: {names}")
    print(
        f"derived {sum(len(m.functions) for m in mods)} functions in {len(mods)} modules "
        f"in {elapsed:.1f} s; wrote {len(changed)} changed file(s) of {len(files)}."
    )
    return 0


def check_paper(args) -> int:
    """Write the paper check's report to ``args.out`` (default `report_path`), with the
    simulated numbers of ``args.evidence`` (a function, or None: those rows say "not
    checked")."""
    from .paper_check import report_path, write_report

    return write_report(Path(args.out) if args.out else report_path(), args.evidence)
