"""Sphinx configuration of the fricgen documentation (MyST markdown, notebooks through myst-nb, the furo theme).

Build: ``sphinx-build -W --keep-going -b html docs docs/_build/html`` (``pip install -e ".[docs]"``).
tests/test_docs.py builds it the same way, warnings as errors. How the site renders math offline and
executes the tutorials: docs/developer/docs-site.md.
"""

import importlib.metadata
import os
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent / "_ext"))

project = "fricgen"
author = "the fricgen authors"
copyright = "2026, the fricgen authors"
release = importlib.metadata.version("fricgen")
version = release

extensions = [
    "myst_nb",  # MyST markdown pages and the notebooks of notebooks/, executed once and cached (below)
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "sphinx-mathjax-offline",  # MathJax 3 from the docs extra's package, served from _static/mathjax: math renders offline
    "sphinx.ext.viewcode",
    "fricgen_cli",  # docs/_ext/fricgen_cli.py: the command-line reference, generated from the argparse parser
    "fricgen_laws",  # docs/_ext/fricgen_laws.py: the table of the built-in catalogue, read from its law files
]

exclude_patterns = ["_build", "Thumbs.db", ".DS_Store", "**.ipynb_checkpoints"]
source_suffix = {".md": "myst-nb", ".ipynb": "myst-nb"}

myst_enable_extensions = ["dollarmath", "amsmath", "deflist", "colon_fence"]
myst_heading_anchors = 3  # GitHub-style anchors, so `physics.md#the-pairwise-contact-step` links resolve
# The tutorials run once, with small workloads, and their outputs (figures, printed results) are kept in
# a jupyter-cache folder, reused while a notebook's code is unchanged (delete the folder to rerun them).
# The test suite hands over the folder that its executed_notebooks fixture filled, so that the suite
# runs each notebook once (tests/conftest.py).
nb_execution_mode = "cache"
nb_execution_cache_path = os.environ.get("FRICGEN_DOCS_NOTEBOOK_CACHE") or str(Path(__file__).parent / "_build" / ".jupyter_cache")
nb_execution_in_temp = True  # a notebook's laws/ folder goes to a temporary folder, not into docs/
nb_execution_timeout = 900
nb_execution_raise_on_error = True
os.environ.setdefault("FRICGEN_NOTEBOOK_SMALL", "1")

# viewcode's "[docs]" links back from a source page name the module an object was first documented
# under; for a name re-exported by a package (fricgen.load_law, fricgen.derive.verify) that anchor does
# not exist. Not following imports links each source page to the objects of its own module only.
viewcode_follow_imported_members = False

autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_typehints_description_target = "documented"  # types of documented arguments; a dataclass's fields carry their own
# Documented members only: a dataclass's fields are listed once, in its docstring's Attributes (shown as a
# field list, napoleon_use_ivar); every public callable and property has a docstring (tests/test_api_docs.py).
autodoc_default_options = {"members": True, "exclude-members": "SECTION"}
napoleon_google_docstring = True  # older docstrings (Args:, Returns:)
napoleon_numpy_docstring = True  # the public API's (Parameters, Returns with units; tests/test_api_docs.py)
autodoc_preserve_defaults = True  # a default renders as written (catalogue=CATALOGUE), not as this machine's path
napoleon_use_rtype = False
napoleon_use_ivar = True  # Attributes as a field list of the class

html_theme = "furo"
html_title = f"fricgen {release}"
html_static_path = ["_static"]
html_css_files = ["fricgen.css"]  # wide tables and code scroll (docs/_static/fricgen.css)
pygments_style = "sphinx"
smartquotes = False  # "--laws" stays two hyphens in prose and in the help texts of the CLI reference
