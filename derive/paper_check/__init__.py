"""``python -m derive check-paper``: the paper's equations and claims against the derivation.

Every numbered equation transcribed in `beltmdsm.derive.paper` is compared with the
expression the package derives, symbolically or, where SymPy cannot decide, with
mpmath at 50 digits at seeded points (a difference is always a numeric
counterexample); the paper's claims in words are re-derived; both are checked for
every friction law of the registry, so that a row or claim that holds for
Coulomb's law only says so. One module per concept:

* `beltmdsm.derive.paper_check.engine`: the comparison of a printed and a derived object,
  the variants of a row and their status;
* `beltmdsm.derive.paper_check.rows`: the rows, one per numbered equation, in paper order;
* `beltmdsm.derive.paper_check.claims`: the claims in words (two of them read the simulation's
  numbers, handed in by the command line: beltmdsm/paper_reports/contraction_evidence.py);
* `beltmdsm.derive.paper_check.report`: the Markdown report (`report`, `write_report`,
  `report_path`).
"""

from .claims import Claim, ClaimResult, check_claim, claims
from .engine import DIGITS, POINTS, REPORT, Outcome, Row, RowResult, Variant, check_row, compare
from .report import report, report_path, run, write_report
from .rows import rows

__all__ = [
    "Variant",
    "Row",
    "Outcome",
    "RowResult",
    "Claim",
    "ClaimResult",
    "compare",
    "check_row",
    "check_claim",
    "rows",
    "claims",
    "run",
    "report",
    "write_report",
    "report_path",
    "REPORT",
    "DIGITS",
    "POINTS",
]
