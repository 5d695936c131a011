"""Sphinx configuration: MyST pages with real maths (MathJax shipped with the pages), the API
from the docstrings, and pages generated at build time (``_ext/strand_docs.py``: the settings
reference from the settings classes, the demos as tutorials)."""

import sys
from pathlib import Path

import strand

sys.path.insert(0, str(Path(__file__).parent / "_ext"))

project = "strand"
author = "the strand developers"
copyright = "2026, the strand developers"
release = strand.__version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    # MathJax in the build (_static/mathjax), not from a CDN: the maths renders offline
    "sphinx-mathjax-offline",
    "strand_docs",
]
myst_enable_extensions = ["dollarmath", "amsmath"]
myst_heading_anchors = 3
source_suffix = {".md": "markdown"}
exclude_patterns = ["_build", "_ext"]
autodoc_member_order = "bysource"
autodoc_default_options = {"members": True, "show-inheritance": True}
autodoc_typehints = "description"
autodoc_typehints_format = "short"
python_use_unqualified_type_names = True
napoleon_google_docstring = True
suppress_warnings = ["myst.header"]
html_theme = "alabaster"
html_static_path = ["_static"]
html_css_files = ["strand.css"]  # the tutorials' printed output, the gallery
html_theme_options = {"page_width": "1100px", "sidebar_width": "230px"}
