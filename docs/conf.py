"""Sphinx configuration of the documentation site (``docs/``).

Build it from the repository root with ``python -m sphinx -W -n -b html docs build/docs``
(then open ``build/docs/index.html``) after ``python -m pip install -e ".[docs]"``;
tests/test_docs_site.py builds it the same way.
The stack is the scientific Python one (numpy, SciPy, python-control): Sphinx with
numpydoc and autosummary for the API from the docstrings, MyST for the Markdown pages of
``docs/`` (which ``beltmdsm docs`` also prints), myst-nb for the notebooks,
sphinx-argparse for the command line, and the PyData theme.
"""

import os
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
sys.path.insert(0, str(DOCS / "_ext"))
sys.path.insert(0, str(DOCS.parent))  # the checkout's package, also when not installed

project = "beltmdsm"
author = "the beltmdsm authors"
copyright = "the beltmdsm authors, MIT licence"
release = version = "0.1.0"

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.intersphinx",
    "numpydoc",
    "myst_nb",
    "sphinxarg.ext",
    "beltmdsm_site",  # docs/_ext/beltmdsm_site.py: the pages generated from the package
    "mathtext_math",  # docs/_ext/mathtext_math.py: math drawn at build, read offline
]
html_math_renderer = "mathtext"

source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}
root_doc = "index"
exclude_patterns = [
    "_build",
    "_ext",
    "tutorials/notebooks/_nbutil.py",
    "**.ipynb_checkpoints",
]
templates_path = ["_templates"]

# -- API from the docstrings ------------------------------------------------------------
autosummary_generate = True
autosummary_imported_members = False
autodoc_typehints = "none"  # numpydoc's Parameters sections say the types
autodoc_member_order = "bysource"
numpydoc_show_class_members = False  # the dataclasses' fields are in their docstrings
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
# intersphinx needs the network; the site builds without it (links to numpy stay text)
intersphinx_mapping = {}
# `name` in a docstring stays text (the default role). "autolink" would link the names
# the site documents, but with -n every other name it meets (private modules, constants)
# is an error: 720 of them with every module of beltmdsm documented, on 2026-11-27.

# -- MyST and notebooks -----------------------------------------------------------------
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 4  # GitHub's anchors: docs/modelling.md#tension works in the site
# Notebooks run at build in quick mode (BELTMDSM_FULL unset: coarse grids); set
# BELTMDSM_DOCS_EXECUTE=off to build without running them (their pages then have no
# output), as tests/test_docs_site.py's quick build does for the paper's notebooks.
# 'cache': jupyter-cache keeps each executed notebook beside the output folder
# (build/.jupyter_cache for build/docs) and reruns only a notebook or code that changed
# the notebook's text; it does not see a change of the package, so after one, rebuild
# with -D nb_execution_mode=force (or delete that folder) to redraw the figures.
nb_execution_mode = os.environ.get("BELTMDSM_DOCS_EXECUTE", "cache")
nb_execution_timeout = 600
nb_execution_raise_on_error = True
nb_execution_show_tb = True
nb_merge_streams = True

# X1' is a derivative, not a quotation: no typographic quotes
smartquotes = False

# -- HTML -------------------------------------------------------------------------------
html_theme = "pydata_sphinx_theme"
html_title = "beltmdsm"
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "secondary_sidebar_items": ["page-toc"],
}
html_static_path = []
html_copy_source = False
html_show_sourcelink = False
