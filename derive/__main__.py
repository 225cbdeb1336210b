"""``python -m derive``: the package's command line.

The derive commands (regenerate ``generated/``, ``--check``, ``check-paper``) are
`beltmdsm.derive.cli`'s; the runtime commands (simulate, sweep, ...) are `beltmdsm.cli`'s, which
builds on it. This entry point is the one place in derive/ that reaches the runtime:
where it cannot be imported (a copy of derive/ alone), the derive commands still run.
"""

import sys

try:
    from beltmdsm.cli import main
except ImportError:
    from .cli import main

sys.exit(main())
