"""Math pre-rendered at build: matplotlib's mathtext draws each formula as inline SVG.

The site builds and reads offline (issue 37 item 4): MathJax, Sphinx's default, loads
its script from a CDN when a page is opened, so a reader without the network saw raw
``$V_b$``. matplotlib, a dependency of the package, renders the TeX subset the pages
use (Greek letters, sub- and superscripts, fractions, roots, accents) to SVG paths,
with no font or script needed by the browser. A few TeX spellings mathtext lacks are
mapped to its own (`SPELLINGS`); a formula it cannot parse fails the build with its
text, so a page never shows raw TeX.
"""

from __future__ import annotations

import io
import re

from docutils import nodes

#: TeX spellings mathtext does not know, and its own for them.
SPELLINGS = {
    r"\ge ": r"\geq ",
    r"\le ": r"\leq ",
    r"\iff": r"\Leftrightarrow",
    r"\big[": "[",
    r"\big]": "]",
    r"\big(": "(",
    r"\big)": ")",
}


def svg(latex: str) -> str:
    """The formula ``latex`` (without dollars) as an inline ``<svg>`` element.

    Raises
    ------
    ValueError
        Naming the formula, where mathtext cannot parse it.
    """
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib import mathtext, rc_context

    text = " ".join(latex.split())  # mathtext reads one line
    for tex, own in SPELLINGS.items():
        text = text.replace(tex, own)
    text = re.sub(r"\\ge$", r"\\geq", text)
    # glyphs as paths (no font needed), ids salted by a constant: the same text each build
    with rc_context({"svg.fonttype": "path", "svg.hashsalt": "beltmdsm"}):
        try:
            buffer = io.BytesIO()
            mathtext.math_to_image(f"${text}$", buffer, format="svg", dpi=72)
        except ValueError as err:
            raise ValueError(f"mathtext cannot draw ${latex}$: {err}") from err
    body = buffer.getvalue().decode()
    body = body[body.index("<svg") :]
    # matplotlib writes the TeX as a comment too: the page shows the drawing only
    return re.sub(r"<metadata>.*?</metadata>|<!--.*?-->", "", body, flags=re.S)


def visit_inline(self, node: nodes.math) -> None:
    self.body.append(f'<span class="math" title="{self.encode(node.astext())}">')
    self.body.append(svg(node.astext()))
    self.body.append("</span>")
    raise nodes.SkipNode


def visit_block(self, node: nodes.math_block) -> None:
    self.body.append(self.starttag(node, "div", CLASS="math"))
    for line in re.split(r"\\\\|\n\s*\n", node.astext()):
        if line.strip():
            self.body.append(f"<p>{svg(line)}</p>")
    self.body.append("</div>")
    raise nodes.SkipNode


def setup(app):
    app.add_html_math_renderer("mathtext", (visit_inline, None), (visit_block, None))
    return {"parallel_read_safe": True, "parallel_write_safe": True}
