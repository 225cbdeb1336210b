"""``validate``: write VALIDATION.md (`beltmdsm.paper_reports.validation`)."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..flags import (
    cache_dir_from,
    cache_parent,
    executor_from,
    executor_parent,
    model_parent,
    output_file,
)
from ..running import register


def add(commands, name: str) -> None:
    sub = register(
        commands,
        name,
        run,
        [model_parent(parameters=False, options=("tension",)), executor_parent(), cache_parent()],
        help="write VALIDATION.md",
        description="Write VALIDATION.md: the Floquet bands, the simulated omega1-peak "
        "ranges and the predicted unstable ranges of Vb for the base set and the cases "
        "of Figs. 17-21.",
    )
    sub.add_argument(
        "--quick",
        action="store_true",
        help="1 m/s grid and 300 s runs instead of 0.25 m/s and 1000 s",
    )
    sub.add_argument(
        "--out",
        type=output_file,
        default="VALIDATION.md",
        help="output file (default: VALIDATION.md in the current folder)",
    )
    sub.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")


def run(args: argparse.Namespace) -> int:
    from ...paper_reports import validation
    from .. import text

    with executor_from(args) as executor:
        results = validation.validate(
            args.quick,
            tension=args.tension,
            executor=executor,
            cache_dir=cache_dir_from(args),
            progress=not args.no_progress,
        )
    Path(args.out).write_text(validation.render_markdown(results, args.quick))
    print(text.validation(results, args.out))
    return 0
