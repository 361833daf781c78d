"""Sphinx configuration of the softimpact documentation (``make docs``: warnings are errors).

The gallery shows the scripts of ``examples/``; they are executed by ``tests/test_examples.py``,
not by the docs build, unless ``SOFTIMPACT_DOCS_RUN_EXAMPLES=1`` (then sphinx-gallery runs them
and the pages carry their figures).
"""

import os
import sys
from pathlib import Path

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE / "_ext"))

import softimpact  # noqa: E402

project = "softimpact"
author = "softimpact developers"
copyright = "softimpact developers, MIT licence"
release = version = softimpact.__version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.mathjax",
    "numpydoc",
    "sphinx_click",
    "sphinx_gallery.gen_gallery",
    "casekeys",
    "plaindoc",
]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build", "gallery/*.ipynb", "gallery/*.py", "gallery/*.zip", "gallery/*.json"]
myst_enable_extensions = ["dollarmath"]
myst_heading_anchors = 3
suppress_warnings = ["myst.header"]

autodoc_member_order = "bysource"
autodoc_typehints = "none"  # numpydoc sections and the docstrings carry the types and units
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
# A public function or class of the API reference without a docstring fails the build (-W): GL08 of
# numpydoc's validation, with undocumented members listed (api.rst's :undoc-members:). Methods are
# exempt: the protocols, laws and case kinds document their methods in the class docstring.
numpydoc_validation_checks = {"GL08"}
numpydoc_validation_exclude = {r"\.[A-Z]\w*\.\w+$"}

run_examples = os.environ.get("SOFTIMPACT_DOCS_RUN_EXAMPLES", "") == "1"
sphinx_gallery_conf = {
    "examples_dirs": str(HERE.parent / "examples"),
    "gallery_dirs": "gallery",
    "filename_pattern": r"/\d\d_",
    "plot_gallery": run_examples,
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
}

html_theme = "alabaster"
html_title = f"softimpact {release}"
html_static_path = []
