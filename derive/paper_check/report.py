"""The report of the paper check and its command: ``python -m derive check-paper``.

`run` checks every row (`beltmdsm.derive.paper_check.rows`) and every claim
(`beltmdsm.derive.paper_check.claims`); `report` writes the Markdown report, deterministic
(seeded points, rows in paper order, no timings), through `beltmdsm.derive.codegen.write`;
`main` is the command with its own argparse.
"""

from __future__ import annotations

import re
import time
from pathlib import Path

from .. import codegen, laws
from .claims import check_claim, claims
from .engine import DIGITS, POINTS, REPORT, check_row
from .rows import rows

__all__ = ["run", "report", "report_path", "write_report"]

# Report ----------------------------------------------------------------------------------


def run(selected: tuple[str, ...] | None = None, evidence=None):
    """Check the rows (all, or those whose key is in ``selected``) and every claim
    (``evidence``: the simulated numbers, `beltmdsm.derive.paper_check.claims.claims`)."""
    results = tuple(check_row(r) for r in rows() if selected is None or r.key in selected)
    claim_results = tuple(check_claim(c) for c in claims(evidence)) if selected is None else ()
    return results, claim_results


def _laws(result) -> str:
    """The friction laws a row holds for: all, or the ones whose derivation is Coulomb's."""
    if len(result.laws) == len(laws.choices("friction")):
        return "every law"
    return f"{', '.join(result.laws)} only ({result.law_detail})"


def _cell(text: str) -> str:
    return re.sub(r"\s+", " ", text.replace("|", "\\|")).strip()


def report(results, claim_results) -> str:
    """The Markdown report (deterministic: no timings, rows in paper order)."""
    counts = {"matches": 0, "matches under a convention": 0, "differs": 0}
    for r in results:
        key = "matches under a convention" if r.status.startswith("matches under") else r.status
        counts[key] += 1
    problems = [p for r in results for p in r.problems]
    lines = [
        "# The paper's equations and claims against the derivation",
        "",
        "Written by `python -m derive check-paper` (`derive/paper_check/`); the "
        "transcriptions, typed by hand exactly as printed, are in `derive/paper.py`. "
        "Do not edit: rerun the command.",
        "",
        "The paper's model has Coulomb friction (Eq. 3). Each row whose derivation takes "
        "the friction law is also derived for every other law of the registry "
        "(`derive/laws.py`); the column `friction laws` says which laws the row holds "
        "for, and where another law's derivation differs, with a numeric example.",
        "",
        f"Each equation is compared symbolically (`expand`, `cancel`, `simplify` under "
        f"the symbols' assumptions); where that does not decide, with mpmath at {DIGITS} "
        f"digits at {POINTS} seeded random points (relative agreement 1e-40 required). "
        "The `decided by` column says which. A difference is always a numeric "
        "counterexample; examples use the base set of Fig. 2 with `Vb = 4` and the "
        "tangential `Vhat` (8.521) where it fixes every symbol. Conventions: `paper` = "
        "Eq. A4 as printed (`+mu_bar F_n`, `mu_bar` of Eq. 23), `consistent` = the sign "
        "of Eq. 4 (`-mu_bar(Z1' - Vb) F_n`), docs/modelling.md#friction-sign.",
        "",
        f"**Summary:** {len(results)} equation rows: {counts['matches']} match, "
        f"{counts['matches under a convention']} match under one convention only, "
        f"{counts['differs']} differ. {len(claim_results)} claims: "
        f"{sum(c.status == 'holds' for c in claim_results)} hold, "
        f"{sum(c.status.startswith('holds under') for c in claim_results)} hold under "
        f"one reading, {sum(c.status == 'does not hold' for c in claim_results)} do not hold.",
        "",
    ]
    if problems:
        lines += ["**Check the explanations:** " + "; ".join(problems), ""]
    lines += [
        "## Equations",
        "",
        "| equation | content | status | friction laws | decided by | difference |",
        "|---|---|---|---|---|---|",
    ]
    for r in results:
        methods = "; ".join(
            (f"`{v.label}`: " if v.label and len(r.row.variants) > 1 else "") + o.method
            for v, o in zip(r.row.variants, r.outcomes)
        )
        lines.append(
            f"| {r.row.key} | {_cell(r.row.content)} | {r.status} | {_cell(_laws(r))} | "
            f"{_cell(methods)} | {_cell(r.explanation)} |"
        )
    lines += [
        "",
        "## Claims in words",
        "",
        "| claim | where | the paper says | status | friction laws | evidence |",
        "|---|---|---|---|---|---|",
    ]
    for c in claim_results:
        lines.append(
            f"| {c.claim.key} | {c.claim.where} | {_cell(c.claim.text)} | "
            f"{c.status} | {_cell(c.laws)} | {_cell(c.evidence)} |"
        )
    lines += [
        "",
        "## Transcription choices",
        "",
        "- Eqs. 5-8 and A3-A6 are transcribed as the right-hand sides of the state "
        "equations they define (Eq. 5 `Y1 = X1'` is `X1' = Y1`).",
        "- Eq. 4 is solved for the accelerations before the comparison (the mass "
        "matrix is the identity); Eqs. 12 and 26 use the printed `J^0` and `J_f^0`, "
        "Eq. 27 the printed `a1..a4`, so they inherit any difference of those.",
        "- Eq. A4's `mu_bar` has no printed argument; it is Eq. 23's `mu_bar(Z1' - Vb)`. "
        "In Eqs. 18-21 and A1-A2 `mu_bar` is the MDSM's average of the friction law "
        "(`beltmdsm.derive.mdsm`; the paper's is Coulomb's), `mu` the law itself.",
        "- Eq. 15 defines the average; it is checked by applying the printed integral "
        "to harmonic fast motions `Phi_i = A_i sin(theta + phi_i)` (which satisfy "
        "`<Phi> = 0`) and comparing with the averages the MDSM derivation uses.",
        "- In Eqs. A1-A2 a prime is `d/dtheta`, a dot `d/dtau`, and `sin(Omega_e tau)` is "
        "the fast phase `sin(theta)`; Eqs. 13-14 write `Omega` for `Omega_e`.",
        '- Eq. 25\'s slope is stated "for `Vhat > Vb`" and is compared there '
        "(`Vhat = Vb + d`, `d > 0`).",
        "",
    ]
    return "\n".join(lines)


def report_path() -> Path:
    """Where the report goes by default: generated/ in a source checkout, else the current
    folder (an installed package's files are the install's)."""
    return codegen.GENERATED / REPORT if codegen.source_checkout() else Path(REPORT)


def write_report(path: Path, evidence=None) -> int:
    """Run the check, write the report to ``path`` and print a summary.

    ``evidence`` returns the simulated numbers of two claims (`claims.claims`). Returns
    0 whatever the paper says; a broken check raises.
    """
    start = time.perf_counter()
    results, claim_results = run(evidence=evidence)
    text = report(results, claim_results)
    changed = not path.exists() or path.read_text() != text
    if changed:
        path.write_text(text)
    statuses = [r.status for r in results]
    print(
        f"{len(results)} equation rows: {statuses.count('matches')} match, "
        f"{sum(s.startswith('matches under') for s in statuses)} match under one "
        f"convention, {statuses.count('differs')} differ; {len(claim_results)} claims: "
        f"{sum(c.status == 'holds' for c in claim_results)} hold, "
        f"{sum(c.status.startswith('holds under') for c in claim_results)} hold under "
        f"one reading, {sum(c.status == 'does not hold' for c in claim_results)} do not."
    )
    for r in results:
        for p in r.problems:
            print(f"WARNING: {p}")
    print(
        f"{path} ({'updated' if changed else 'unchanged'}) in {time.perf_counter() - start:.1f} s"
    )
    return 0
