"""The top of the command line and the derive commands.

One argparse tree::

    python -m derive [--check]        derive everything, regenerate generated/ (or check it)
    python -m derive check-paper      compare the paper with the derivation
    python -m beltmdsm simulate|sweep|...   the runtime commands (beltmdsm.cli)

This module holds the top of the tree and the derive commands; `main` takes an
``extend`` hook that hangs more commands on it (the runtime's, `beltmdsm.cli`, whose
``main`` calls this one). derive/ itself never imports the runtime: ``python -m
derive`` (derive/__main__.py) is the one place that hands the command line to it.
Nothing symbolic is imported until a derive command runs, so the runtime commands
never load SymPy.

The regeneration prints one line per module on stderr as it derives it, with its time
(stdout keeps the summary). A law that `beltmdsm.derive.laws.register` refuses
(`beltmdsm.derive.lawcheck.UnsupportedLaw`) is one line too, exit status 2.

Every error in a command line is one line on stderr and exit status 2 (`Parser`);
`main` returns the exit status, which ``python -m derive`` and the console script
pass to ``sys.exit``.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

__all__ = ["main", "build_parser", "Parser", "UsageError", "writable_file", "writable_folder"]


class UsageError(Exception):
    """A bad command line: one line for stderr (the program, ``error:`` and why)."""


class Parser(argparse.ArgumentParser):
    """An ``ArgumentParser`` whose errors are one line, raised as `UsageError`.

    argparse prints the whole usage before its error, which for the runtime
    commands is a screenful of flags; the message names the flag, and ``--help``
    shows the usage. Raising (instead of exiting) lets `main` return the status.
    """

    def error(self, message):
        raise UsageError(f"{self.prog}: error: {message} (--help for usage)")


def _progress(spec, seconds):
    """One line on stderr per derived module, as the derivation goes (stdout keeps the
    summary that scripts read)."""
    print(f"derived generated/{spec.name}.py in {seconds:.1f} s", file=sys.stderr, flush=True)


def _generate(args) -> int:
    try:
        from . import codegen, modules
    except ValueError as err:  # a law refused at `register` (derive.lawcheck.UnsupportedLaw)
        if type(err).__name__ != "UnsupportedLaw":
            raise
        raise UsageError(f"{args.parser.prog}: error: {err}") from None

    root = codegen.GENERATED if args.out is None else Path(args.out)
    if args.out is None and not args.check and not codegen.source_checkout():
        args.parser.error(
            f"regenerating generated/ needs a source checkout: this one is installed "
            f"({codegen.GENERATED.parent}); give --out DIR to write a complete copy there"
        )
    if args.out is not None and not args.check:
        problem = writable_folder(root)  # before the derivation, not after it
        if problem:
            args.parser.error(f"argument --out: {problem}")
    start = time.perf_counter()
    mods = modules.all_modules(progress=_progress)
    files = codegen.render_all(mods)
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


def _check_paper(args) -> int:
    from .paper_check import report_path, write_report

    return write_report(Path(args.out) if args.out else report_path(), args.evidence)


def _prog():
    """How the user called the command line: ``beltmdsm``, ``python -m beltmdsm`` or
    ``python -m derive``."""
    path = sys.argv[0] if sys.argv else ""
    if os.path.basename(path) == "__main__.py":
        return f"python -m {os.path.basename(os.path.dirname(path))}"
    return "beltmdsm" if os.path.basename(path) == "beltmdsm" else "python -m derive"


def _folder(s):
    """A folder to write into: created if missing; not an existing file."""
    if Path(s).exists() and not Path(s).is_dir():
        raise argparse.ArgumentTypeError(f"{s} exists and is not a folder")
    return s


def writable_folder(folder):
    """Why ``folder`` (created if missing) cannot be written, or None: a test file of a
    unique name is created in it and removed, since ``os.access`` passes for root
    where writing fails (``/proc``)."""
    try:
        Path(folder).mkdir(parents=True, exist_ok=True)
        fd, probe = tempfile.mkstemp(dir=folder, prefix=".probe-")
        os.close(fd)
        os.remove(probe)
    except OSError as err:
        return f"{folder} cannot be written ({err.strerror or err})"
    return None


def writable_file(s):
    """An argparse type: a file to write, checked by writing before anything is computed.

    Its folder must exist and it must not be a folder; an existing file is opened for
    appending (and left as it was), a new one is tried as a sibling temporary file,
    created and removed: ``os.access`` passes for root where writing fails, and a
    report computed for two minutes was lost at the end (issue 28).
    """
    path = Path(s)
    folder = path.parent if str(path.parent) else Path(".")
    if not folder.is_dir():
        raise argparse.ArgumentTypeError(f"folder {folder} does not exist")
    if path.is_dir():
        raise argparse.ArgumentTypeError(f"{path} is a folder, not a file")
    try:
        if path.exists():
            with open(path, "ab"):
                pass
        else:
            fd, probe = tempfile.mkstemp(dir=folder, prefix=f".{path.name}.", suffix=".tmp")
            os.close(fd)
            os.remove(probe)
    except OSError as err:
        raise argparse.ArgumentTypeError(
            f"{path} cannot be written ({err.strerror or err})"
        ) from None
    return s


def build_parser(prog=None, extend=None, evidence=None):
    """The command-line tree (`Parser`); ``extend(commands)`` adds more commands.

    ``evidence`` returns the simulated numbers of the paper check
    (`beltmdsm.derive.paper_check.claims.claims`); the runtime's command line hands it over.

    The runtime's commands import ``generated/``, which ``python -m derive`` may be
    about to regenerate, or which may be absent from a copy of ``derive/`` alone: if
    ``extend`` fails, the derive commands still work and the reason is kept in
    ``parser.unavailable`` (else None).
    """
    parser = Parser(
        prog=prog or _prog(),
        description="Derive the model symbolically and regenerate generated/ "
        "(no command), or run one of the commands.",
    )
    parser.add_argument(
        "--check",
        action="store_true",
        help="do not write; exit 1 and name the stale files if "
        "generated/ differs from the derivations",
    )
    parser.add_argument(
        "--out",
        type=_folder,
        default=None,
        metavar="DIR",
        help="write (or check) a complete copy of generated/ in DIR instead of the "
        "package's generated/ (which only a source checkout may rewrite)",
    )
    commands = parser.add_subparsers(dest="command", metavar="COMMAND", title="commands")
    paper = commands.add_parser(
        "check-paper",
        help="compare the paper's equations and claims with the derivation",
        description="Compare the paper's equations and claims with the derivation; write "
        "the report PAPER_CHECK.md.",
    )
    paper.add_argument(
        "--out",
        type=writable_file,
        default=None,
        metavar="FILE",
        help="the report (default: generated/PAPER_CHECK.md in a source checkout, else "
        "PAPER_CHECK.md in the current folder)",
    )
    paper.set_defaults(run=_check_paper, evidence=evidence, parser=paper)
    parser.unavailable = None
    if extend is not None:
        try:
            extend(commands)
        except Exception as err:  # noqa: BLE001 (whatever a broken generated/ raises)
            parser.unavailable = parser.epilog = (
                f"the runtime commands cannot be loaded: {type(err).__name__}: {err}"
            )
    return parser


def _needs_runtime(argv):
    """False for the regeneration and check-paper: their command lines must not need
    generated/ (check-paper's simulated rows import the runtime when they run)."""
    return not (set(argv) <= {"--check"} or argv[:1] == ["check-paper"])


def main(argv=None, *, extend=None, evidence=None) -> int:
    """Run the command line ``argv`` (default ``sys.argv[1:]``); return the exit status.

    ``extend(commands)`` hangs more commands on the tree (not called for the
    regeneration and check-paper, which must not need ``generated/``); ``evidence``
    returns the paper check's simulated numbers (`build_parser`).

    0: done; 1: a check failed (``--check``) or the system refused (a file, the
    network), or the reader of the output went away (``| head``, quietly); 2: a bad
    command line or parameter, reported in one line on stderr.
    A simulation that did not reach its end returns 2 as well (``simulate``).
    """
    argv = sys.argv[1:] if argv is None else list(argv)
    parser = build_parser(extend=extend if _needs_runtime(argv) else None, evidence=evidence)
    try:
        args = parser.parse_args(argv)
        if args.command is None:
            args.parser = parser
            status = _generate(args)
        else:
            if args.check:
                parser.error("--check applies to the regeneration, not to a command")
            status = args.run(args)
        sys.stdout.flush()  # a reader gone (`| head`) shows here, not at exit
        return status
    except UsageError as err:
        print(err, file=sys.stderr)
        if parser.unavailable:
            print(parser.unavailable, file=sys.stderr)
        return 2
    except BrokenPipeError:
        # the reader of the output went away (`| head`): end quietly, as the Python
        # documentation advises (the signal module's note on SIGPIPE); what is still
        # buffered goes to the null device, not to a second error at exit
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 1
    except SystemExit as done:  # --help, or a command that exits
        if done.code is None or isinstance(done.code, int):
            return done.code or 0
        print(done.code, file=sys.stderr)
        return 1
