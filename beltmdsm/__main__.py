"""``python -m beltmdsm``: the command line (`beltmdsm.cli`)."""

import sys

from .cli import main

sys.exit(main())
