"""Sphinx configuration of the fricgen documentation (MyST markdown, notebooks through myst-nb, the furo theme).

Build: ``sphinx-build -W --keep-going -b html docs docs/_build/html`` (``pip install -e ".[docs]"``).
tests/test_docs.py builds it the same way, warnings as errors.
"""

import importlib.metadata
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent / "_ext"))

project = "fricgen"
author = "the fricgen authors"
copyright = "2026, the fricgen authors"
release = importlib.metadata.version("fricgen")
version = release

extensions = [
    "myst_nb",  # MyST markdown pages and the notebooks of notebooks/ (not executed here: tests/test_notebooks.py runs them)
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "fricgen_cli",  # docs/_ext/fricgen_cli.py: the command-line reference, generated from the argparse parser
    "fricgen_laws",  # docs/_ext/fricgen_laws.py: the table of the built-in catalogue, read from its law files
]

exclude_patterns = ["_build", "Thumbs.db", ".DS_Store", "**.ipynb_checkpoints"]
source_suffix = {".md": "myst-nb", ".ipynb": "myst-nb"}

myst_enable_extensions = ["dollarmath", "amsmath", "deflist", "colon_fence"]
myst_heading_anchors = 3  # GitHub-style anchors, so `physics.md#the-pairwise-contact-step` links resolve
nb_execution_mode = "off"

autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_typehints_description_target = "documented"  # types of documented arguments; a dataclass's fields carry their own
autodoc_default_options = {"members": True, "undoc-members": True, "exclude-members": "SECTION"}
napoleon_google_docstring = True
napoleon_numpy_docstring = False
napoleon_use_rtype = False
napoleon_use_ivar = True  # "Attributes:" as a field list: dataclass fields are also documented as members

html_theme = "furo"
html_title = f"fricgen {release}"
html_static_path = []
pygments_style = "sphinx"
smartquotes = False  # "--laws" stays two hyphens in prose and in the help texts of the CLI reference
