"""``beltmdsm docs``: the documents the help texts cite, by page and section."""

import pytest

from beltmdsm.cli import main
from beltmdsm.cli.commands import docs


def test_a_cited_section_prints_alone_with_its_subsections(capsys):
    assert main(["docs", "docs/modelling.md#tension"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("## Tension\n")
    assert "### Without tension the vibration cannot exist" in out
    assert "## What unstable means" not in out  # the next section of the same level


def test_the_short_form_and_the_whole_page(capsys):
    assert main(["docs", "modelling#tension"]) == 0
    short = capsys.readouterr().out
    assert main(["docs", "modelling"]) == 0
    page = capsys.readouterr().out
    assert page.startswith("# Modelling choices") and short in page


@pytest.mark.parametrize(
    ("name", "why"),
    [("nowhere", "no page 'nowhere'"), ("modelling#nowhere", "no section 'nowhere'")],
)
def test_an_unknown_name_is_one_line_and_status_2(capsys, name, why):
    assert main(["docs", name]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and why in err


def test_anchors_follow_githubs_rule():
    assert docs.anchor("What SymPy decides about the law") == "what-sympy-decides-about-the-law"
    assert docs.anchor("Worked example: viscous plus Coulomb friction") == (
        "worked-example-viscous-plus-coulomb-friction"
    )
