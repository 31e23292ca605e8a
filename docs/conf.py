"""Sphinx configuration of robokin's documentation site (`make docs`, built with -W).

The API reference is generated when the build starts (docs/_api_pages.py): one page per public module
and class, so that a new public name appears without editing a page. The notebooks in notebooks/ are
MyST markdown, executed while the site is built.
"""

import pathlib
import sys

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import _api_pages  # noqa: E402

project = "robokin"
author = "the robokin authors"
copyright = "the robokin authors, MIT licence"

extensions = ["myst_nb", "sphinx.ext.autodoc", "sphinx.ext.napoleon", "sphinx.ext.mathjax"]
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb"}
# Figures and their scripts live in docs/ too; only these are pages.
exclude_patterns = ["_build", "**/.ipynb_checkpoints", "jupyter_execute"]
html_theme = "furo"
html_title = "robokin"
html_static_path = []

myst_enable_extensions = ["dollarmath", "colon_fence"]
myst_heading_anchors = 3
# Every notebook runs on each build; a cell that raises fails the build (as -W makes a warning do).
nb_execution_mode = "force"
nb_execution_raise_on_error = True
nb_execution_timeout = 120
nb_merge_streams = True
# sympy's results as their text (Matrix([...])): LaTeX would need MathJax from the network to be read.
nb_mime_priority_overrides = [("html", "text/latex", None)]

autodoc_member_order = "bysource"
autodoc_typehints = "signature"
# The package's own postponed annotations as written (not numpy's ArrayLike expanded into its union).
autodoc_type_aliases = {"numpy.typing.ArrayLike": "numpy.typing.ArrayLike",
                        "numpy.typing.NDArray": "numpy.typing.NDArray"}
autodoc_default_options = {"members": True}
napoleon_google_docstring = True
napoleon_numpy_docstring = True
napoleon_use_rtype = False
# A result's Attributes section as fields: its attributes are described once, by autodoc.
napoleon_use_ivar = True
# A name in a docstring (`q`, `dof`) that several classes define is left unlinked, not an error.
suppress_warnings = ["myst.header", "ref.python"]


def setup(app):
    app.connect("builder-inited", lambda app: _api_pages.write(HERE / "api"))
    app.connect("autodoc-process-signature", _api_pages.clean_signature)
    # After napoleon (priority 500) has turned Args / Returns into fields.
    app.connect("autodoc-process-docstring", _api_pages.clean_docstring, priority=600)
