"""Sphinx configuration: the theory (MyST markdown) and the API reference from the docstrings."""

import strand

project = "strand"
author = "the strand developers"
copyright = "2026, the strand developers"
release = strand.__version__

extensions = ["myst_parser", "sphinx.ext.autodoc", "sphinx.ext.napoleon", "sphinx.ext.mathjax"]
myst_enable_extensions = ["dollarmath"]
source_suffix = {".md": "markdown"}
exclude_patterns = ["_build"]
autodoc_member_order = "bysource"
autodoc_default_options = {"members": True, "show-inheritance": True}
autodoc_typehints = "description"
napoleon_google_docstring = True
suppress_warnings = ["myst.header"]
html_theme = "alabaster"
