"""The flags the commands share, checked when they are parsed.

Declared once, as parent parsers:

* `model_parent`: every model parameter (``beltmdsm.generated.parameters``) as a flag (``--mu_s``
  and ``--mu-s``), checked against its domain (`beltmdsm.model.check_domain`), and the
  model options (`beltmdsm.model.OPTIONS`) with their choices;
* `solver_parent`: the fields of `beltmdsm.settings.SolverSettings`;
* `executor_parent` and `executor_from`: ``--jobs``/``--scheduler`` and the executor
  they ask for; `cache_parent`: the sweep cache; `json_parent`: ``--json``;
* `periods_parent`: ``--periods K``, the response of ``K`` excitation periods;
  `lock_parent`: ``--limit``, the longest lock looked for.

`model_from` builds the `beltmdsm.Model` of a command line once; `settings_from` its
`SolverSettings`. Every flag is checked when it is parsed (finite numbers, domains,
ranges, existing output folders); a bad one is a one-line error naming it, exit status
2 (`beltmdsm.cli.parser.Parser`).
"""

from __future__ import annotations

import argparse
import concurrent.futures as cf
import contextlib
import math
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path

from beltmdsm.generated.parameters import PARAMETERS

from ..model import OPTION_DEFAULTS, OPTION_DOCS, OPTIONS, Model, check_domain
from ..settings import (
    CONTACT_LOSS,
    DEFAULT_T_END,
    MAX_RTOL,
    METHODS,
    SOLVERS,
    SolverSettings,
)
from .parser import in_flags, writable_file

__all__ = [
    "number",
    "integer",
    "output_file",
    "npz_file",
    "POSITIVE",
    "NONNEGATIVE",
    "OPTION_HELP",
    "model_parent",
    "model_from",
    "swept",
    "range_flags",
    "range_from",
    "params_from",
    "solver_parent",
    "settings_from",
    "executor_parent",
    "executor_from",
    "cache_parent",
    "cache_dir_from",
    "json_parent",
    "periods_parent",
    "lock_parent",
]

_MODEL_PARAMS = [p for p in PARAMETERS if p["name"] != "Vhat"]

#: The help of each model option: its choices, each with the registry's one line.
OPTION_HELP = {
    option: f"{option} law (derive/laws.py): "
    + "; ".join(f"{choice}: {doc}" for choice, doc in docs.items())
    for option, docs in OPTION_DOCS.items()
}


def number(check: Callable[[float], bool] | None = None, text: str = "") -> Callable[[str], float]:
    """An argparse type: a finite float, and ``check(x)`` if given ("must be <text>")."""

    def parse(s: str) -> float:
        try:
            x = float(s)
        except ValueError:
            raise argparse.ArgumentTypeError(f"must be a number; got {s!r}") from None
        if not math.isfinite(x):
            raise argparse.ArgumentTypeError(f"must be finite; got {s}")
        if check is not None and not check(x):
            raise argparse.ArgumentTypeError(f"must be {text}; got {s}")
        return x

    return parse


def _parameter(name):
    """An argparse type: a finite float in the domain of model parameter ``name``."""

    def parse(s: str) -> float:
        x = number()(s)
        problem = check_domain(name, x)
        if problem:
            raise argparse.ArgumentTypeError(f"{problem}; got {s}")
        return x

    return parse


def integer(minimum: int, maximum: int | None = None) -> Callable[[str], int]:
    """An argparse type: an integer in ``[minimum, maximum]``."""

    def parse(s: str) -> int:
        try:
            n = int(s)
        except ValueError:
            raise argparse.ArgumentTypeError(f"must be an integer; got {s!r}") from None
        if n < minimum:
            raise argparse.ArgumentTypeError(f"must be >= {minimum}; got {n}")
        if maximum is not None and n > maximum:
            raise argparse.ArgumentTypeError(f"must be <= {maximum}; got {n}")
        return n

    return parse


def output_file(s: str) -> str:
    """A file to write: its folder must exist, it must not be a folder, and it is
    written to (a sibling temporary file) before anything is computed
    (`beltmdsm.cli.parser.writable_file`)."""
    return writable_file(s)


def npz_file(s: str) -> str:
    """`output_file` for ``numpy.savez``, which adds ``.npz`` to a name without it: the
    name it writes."""
    return output_file(s if s.endswith(".npz") else f"{s}.npz")


def _cache_folder(s):
    if s != "default" and Path(s).exists() and not Path(s).is_dir():
        raise argparse.ArgumentTypeError(f"{s} exists and is not a folder")
    return s


POSITIVE = number(lambda x: x > 0, "> 0")
NONNEGATIVE = number(lambda x: x >= 0, ">= 0")


def model_parent(
    *,
    parameters: bool = True,
    exclude: Sequence[str] = (),
    options: Sequence[str] | None = None,
) -> argparse.ArgumentParser:
    """Parent parser: the model parameters as flags and the model options.

    Parameters
    ----------
    parameters : bool
        add a flag per model parameter of ``beltmdsm.generated.parameters.PARAMETERS``
    exclude : tuple of str
        parameters without a flag (``predict`` scans ``Vb`` itself)
    options : tuple of str, optional
        the model options taken (default: all of `beltmdsm.model.OPTIONS`)
    """
    parent = argparse.ArgumentParser(add_help=False)
    if parameters:
        group = parent.add_argument_group("model parameters (default: the base set, Fig. 2)")
        for p in _MODEL_PARAMS:
            if p["name"] in exclude:
                continue
            flags = [f"--{p['name']}"]
            if "_" in p["name"]:
                flags.append(f"--{p['name'].replace('_', '-')}")
            default = (
                f"default: {p['default_from']}"
                if p["default_from"]
                else f"default: {p['base']:g}"
                if p["base"] is not None
                else ""
            )
            group.add_argument(
                *flags,
                dest=p["name"],
                type=_parameter(p["name"]),
                default=None,
                metavar="X",
                help=f"{p['description']} [{p['unit']}]; {default}".rstrip("; "),
            )
    group = parent.add_argument_group("model options")
    for name, choices in OPTIONS.items():
        if options is not None and name not in options:
            continue
        group.add_argument(
            f"--{name}",
            dest=name,
            choices=choices,
            default=OPTION_DEFAULTS[name],
            help=f"{OPTION_HELP[name]} (default: {OPTION_DEFAULTS[name]})".replace("%", "%%"),
        )
    return parent


def params_from(args: argparse.Namespace, skip: Sequence[str] = ()) -> dict[str, float]:
    """The model parameters given as flags (not ``skip``)."""
    return {
        p["name"]: getattr(args, p["name"])
        for p in _MODEL_PARAMS
        if getattr(args, p["name"], None) is not None and p["name"] not in skip
    }


def swept(args: argparse.Namespace, dest: str = "param") -> str:
    """``args.param`` (or the flag ``dest`` that names a walked parameter: ``--x``),
    refused where it is also given as a fixed parameter (``--Vb 3``)."""
    name = getattr(args, dest)
    if getattr(args, name, None) is not None:
        args.parser.error(
            f"argument --{name}: {name} is the parameter walked (--{dest} {name}); drop --{name}"
        )
    return name


def range_flags(sub: argparse.ArgumentParser, axis: str = "") -> None:
    """``--from X --to X`` (``--{axis}-from``, ``--{axis}-to`` for a map's axis): the
    range walked; `range_from` reads and checks it."""
    prefix, dest = (f"--{axis}-", f"{axis}_") if axis else ("--", "")
    sub.add_argument(
        f"{prefix}from",
        dest=f"{dest}start",
        type=number(),
        required=True,
        metavar="X",
        help="lower end of the range, in the parameter's domain",
    )
    sub.add_argument(
        f"{prefix}to",
        dest=f"{dest}stop",
        type=number(),
        required=True,
        metavar="X",
        help=f"upper end of the range, strictly above {prefix}from",
    )


def range_from(args: argparse.Namespace, axis: str = "") -> tuple[float, float]:
    """The range of `range_flags`, refused (exit 2) unless its upper end is above its lower."""
    prefix, dest = (f"--{axis}-", f"{axis}_") if axis else ("--", "")
    lo, hi = getattr(args, f"{dest}start"), getattr(args, f"{dest}stop")
    if not hi > lo:
        args.parser.error(f"argument {prefix}to: must be > {prefix}from ({lo:g}); got {hi:g}")
    return lo, hi


def model_from(args: argparse.Namespace, skip: Sequence[str] = ()) -> Model:
    """The `beltmdsm.Model` of the parameter and option flags (a bad value: exit 2)."""
    options = {name: getattr(args, name) for name in OPTIONS if hasattr(args, name)}
    try:
        return Model(**params_from(args, skip), **options)
    except ValueError as err:
        args.parser.error(str(err))


def solver_parent() -> argparse.ArgumentParser:
    """Parent parser: the fields of `beltmdsm.settings.SolverSettings`."""
    parent = argparse.ArgumentParser(add_help=False)
    s = parent.add_argument_group("solver")
    s.add_argument(
        "--solver",
        choices=SOLVERS,
        default="events",
        help="events: the package's DOP853 integrator on each mode of Eq. (4), switches "
        "located (beltmdsm/integrate/events.py); superposition: the normal motion once "
        "and the tangential one in closed form between switches, handed to events where "
        "its closed forms do not exist (beltmdsm/integrate/superposition.py) "
        "(default: events)",
    )
    s.add_argument(
        "--method",
        choices=METHODS,
        default="DOP853",
        help="the Runge-Kutta method of the integrators (default: DOP853, the only one)",
    )
    s.add_argument(
        "--rtol",
        type=number(
            lambda x: 0 < x <= MAX_RTOL,
            f"> 0 and <= MAX_RTOL = {MAX_RTOL:g} (beltmdsm/settings.py): a looser relative "
            "tolerance keeps no significant digit of a step, so the sign of a switching "
            "function is not resolved",
        ),
        default=1e-10,
        help=f"relative tolerance of the integrators' local error per step, > 0 and <= "
        f"{MAX_RTOL:g} (MAX_RTOL, beltmdsm/settings.py); the "
        "noise floor of the spectrum and the bound of the energy residual follow it "
        "(beltmdsm/run/tolerances.py) (default: 1e-10)",
    )
    s.add_argument(
        "--atol",
        type=POSITIVE,
        default=1e-10,
        help="absolute tolerance of the integrators' local error per step, > 0 (default: 1e-10)",
    )
    s.add_argument(
        "--t-end",
        type=POSITIVE,
        default=DEFAULT_T_END,
        help="simulated time [s], > 0; a run whose memory estimate exceeds MAX_RUN_BYTES "
        f"(beltmdsm/settings.py) is refused (default: {DEFAULT_T_END:g})",
    )
    s.add_argument(
        "--t-discard",
        type=NONNEGATIVE,
        default=None,
        help="start of the steady window [s] (default 30%% of --t-end)",
    )
    s.add_argument(
        "--dt",
        type=POSITIVE,
        default=0.02,
        help="sampling step of the time series [s], > 0; pi/dt must be at least "
        "NYQUIST_MULTIPLE = 8 times the fastest of Omega_t, Omega_n, omega1 "
        "(beltmdsm/settings.py) (default: 0.02)",
    )
    s.add_argument(
        "--on-contact-loss",
        choices=CONTACT_LOSS,
        default="continue",
        help="on loss of contact (the contact's gap closes to 0): go on in flight, or stop "
        "the run (default: continue)",
    )
    return parent


def settings_from(args: argparse.Namespace) -> SolverSettings:
    """The `SolverSettings` of the solver flags (settings that do not fit: exit 2)."""
    try:
        return SolverSettings(
            solver=args.solver,
            method=args.method,
            rtol=args.rtol,
            atol=args.atol,
            t_end=args.t_end,
            t_discard=args.t_discard,
            dt=args.dt,
            on_contact_loss=args.on_contact_loss,
        )
    except ValueError as err:
        # every field is checked alone when parsed: what is left is how they fit together
        said = in_flags(str(err), args.parser, ("t_end", "t_discard", "dt"))
        args.parser.error(f"argument --t-end/--t-discard/--dt: {said}")


def executor_parent() -> argparse.ArgumentParser:
    """Parent parser: where the runs go, ``--jobs`` and ``--scheduler`` (`executor_from`)."""
    parent = argparse.ArgumentParser(add_help=False)
    g = parent.add_argument_group("where the runs go")
    g.add_argument(
        "--jobs",
        type=integer(1),
        default=None,
        help="worker processes (default: all cores; 1: in this process)",
    )
    g.add_argument(
        "--scheduler",
        default=None,
        metavar="ADDRESS",
        help="a dask.distributed scheduler, e.g. tcp://host:8786 (needs the "
        "'dask' extra); overrides --jobs",
    )
    return parent


#: How long an interrupted command waits for the dask scheduler to take back its tasks [s].
CLOSE_S = 1


@contextlib.contextmanager
def executor_from(args: argparse.Namespace) -> Iterator[cf.Executor | str | None]:
    """The executor that ``--scheduler``/``--jobs`` ask for, closed when the block ends.

    Yields
    ------
    ``Client(ADDRESS).get_executor()`` of a dask.distributed cluster for
    ``--scheduler``; ``"serial"`` for ``--jobs 1``; a process pool of ``--jobs N``
    workers; None without either (the sweep opens a pool over the local cores).
    """
    if args.scheduler:
        try:
            from distributed import Client
        except ImportError:
            args.parser.error(
                "argument --scheduler: needs dask.distributed (pip install 'beltmdsm[dask]')"
            )
        try:
            client = Client(args.scheduler, timeout="10s")
        except (OSError, ValueError, TypeError) as err:
            args.parser.error(f"argument --scheduler: cannot connect to {args.scheduler}: {err}")
        executor = client.get_executor()
        try:
            yield executor
        except BaseException:
            # Ctrl-C or a failure: the tasks not finished are cancelled, not waited for
            # (a shutdown that waits ran the whole round on: 308 s, issue 36 item 3);
            # what the workers finished is in the cache already
            executor.shutdown(wait=False)
            client.close(timeout=CLOSE_S)
            raise
        executor.shutdown()
        client.close()
    elif args.jobs == 1:
        yield "serial"
    elif args.jobs:
        from ..batch.pool import process_pool, stop_process_pool

        pool = process_pool(args.jobs)
        try:
            yield pool
        except BaseException:
            # Ctrl-C or a failure: the queued points are not waited for
            stop_process_pool(pool)
            raise
        pool.shutdown()
    else:
        yield None


def cache_parent() -> argparse.ArgumentParser:
    """Parent parser: the sweep cache (`beltmdsm.batch.cache`)."""
    parent = argparse.ArgumentParser(add_help=False)
    g = parent.add_argument_group("cache")
    g.add_argument(
        "--cache-dir",
        type=_cache_folder,
        default="default",
        metavar="FOLDER",
        help="the folder of the sweep cache, refused if it cannot be written (default: "
        "sweeps in $BELTMDSM_CACHE, else in $XDG_CACHE_HOME/beltmdsm-cache, else in "
        "~/.cache/beltmdsm-cache; an empty variable counts as unset)",
    )
    g.add_argument("--no-cache", action="store_true", help="do not use the sweep cache")
    return parent


def cache_dir_from(args: argparse.Namespace) -> str | None:
    return None if args.no_cache else args.cache_dir


def json_parent() -> argparse.ArgumentParser:
    parent = argparse.ArgumentParser(add_help=False)
    parent.add_argument(
        "--json",
        action="store_true",
        help="print the result as one JSON object instead of text (its keys: "
        "docs/reference/json.md, the documentation site's JSON page)",
    )
    return parent


def periods_parent() -> argparse.ArgumentParser:
    """Parent parser: ``--periods K``, the response of ``K`` excitation periods."""
    parent = argparse.ArgumentParser(add_help=False)
    parent.add_argument(
        "--periods",
        type=integer(1),
        default=1,
        metavar="K",
        help="the response of K excitation periods, a phase-locked one for K > 1 (seeded "
        "from the attractor of the period map iterated from rest; default 1)",
    )
    return parent


#: The default of ``--limit``: ``beltmdsm.periodic.locked.LOCK_LIMIT``, written out so that
#: ``--help`` imports no analysis (tests/beltmdsm/cli/test_locked_commands.py keeps them equal).
LOCK_LIMIT = 12


def lock_parent() -> argparse.ArgumentParser:
    """Parent parser: ``--limit``, the longest period a lock is looked for at."""
    parent = argparse.ArgumentParser(add_help=False)
    parent.add_argument(
        "--limit",
        type=integer(1),
        default=LOCK_LIMIT,
        help=f"the longest period looked for, in excitation periods (default {LOCK_LIMIT})",
    )
    return parent
