"""Sphinx configuration of the softimpact documentation (``make docs``: warnings are errors).

The site builds offline: the theme (pydata-sphinx-theme), its fonts and icons, and MathJax
(``sphinx-mathjax-offline``, copied into ``_static/mathjax``) come with the ``docs`` extra; no
page loads a script, a style sheet or a font from another host.

The gallery shows the scripts of ``examples/``. ``make docs`` executes the quick ones
(``QUICK_EXAMPLES``, a few seconds each) and shows their figures; the slow ones (the fit of the
rubber series, the calibration, the sweep: 20 s to a minute each) are shown as code, their
thumbnail taken from a stored figure, ``_static/thumbnails/<example>.png``
(``# sphinx_gallery_thumbnail_path`` in the script). ``python docs/_ext/gallery_figures.py``
runs the slow examples and refreshes those figures. ``SOFTIMPACT_DOCS_RUN_EXAMPLES=all make docs``
executes every example (their pages then carry their figures), ``=none`` none. Every example
runs, its number asserted, in ``tests/test_examples.py`` either way.
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

# Not intersphinx: it downloads the other projects' inventories at every build, and the site
# must build without a network (a lab's machine). Names of numpy, SciPy and Python stay plain text.
extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.mathjax",
    "sphinx-mathjax-offline",  # MathJax 3 from the package into _static/mathjax, mathjax_path pointed there
    "sphinx_copybutton",
    "numpydoc",
    "sphinx_click",
    "sphinx_gallery.gen_gallery",
    "casekeys",
    "catalogue_page",
    "plaindoc",
]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build", "gallery/*.ipynb", "gallery/*.py", "gallery/*.zip", "gallery/*.json"]
myst_enable_extensions = ["dollarmath"]
myst_heading_anchors = 3
suppress_warnings = ["myst.header"]
# Options, paths and units are written as they are typed: no "--out" turned into an en dash, no
# curly quotes in a TOML value.
smartquotes = False

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

# The copy button copies the command or the code, not the prompt, the shell's "$ " or Python's ">>> ".
copybutton_prompt_text = r">>> |\.\.\. |\$ "
copybutton_prompt_is_regexp = True
copybutton_only_copy_prompt_lines = False

# Examples executed by the docs build: about a second each. Measured one at a time, each in a fresh
# process after `import softimpact` (2 cores, load 3): 01 0.7 s, 04 1.0 s, 03 1.5 s; not executed:
# 06 5.2 s (it imports Dask), 02 5.6 s, 05 20 s (about twice that under the test suite's load).
# 08 executed although slower (3 s of CPU: a static Newton and two coupled plate runs), for its figure; 10 likewise (6 s of CPU).
QUICK_EXAMPLES = (
    "01_bar_test",
    "03_beam_table_history",
    "04_impact_on_your_plate",
    "07_hail_on_a_plate",
    "08_hail_on_a_thin_skin",
    "09_your_own_bars",
    "10_delamination_benchmarks",
)
run_examples = os.environ.get("SOFTIMPACT_DOCS_RUN_EXAMPLES", "quick").strip().lower()
if run_examples in ("all", "1"):
    executed = r"/\d\d_[^/]*\.py$"
elif run_examples in ("none", "0"):
    executed = r"^$"
else:
    executed = "/(" + "|".join(QUICK_EXAMPLES) + r")\.py$"
sphinx_gallery_conf = {
    "examples_dirs": str(HERE.parent / "examples"),
    "gallery_dirs": "gallery",
    "filename_pattern": executed,
    "ignore_pattern": r"__init__\.py",
    "plot_gallery": True,
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "matplotlib_animations": False,
    "image_scrapers": ("matplotlib",),
    # No execution-times page: sphinx-gallery's loads jQuery and DataTables from their CDNs.
    "write_computation_times": False,
}

html_theme = "pydata_sphinx_theme"
html_title = f"softimpact {release}"
html_static_path = ["_static"]
html_css_files = ["softimpact.css"]
html_last_updated_fmt = None
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "secondary_sidebar_items": ["page-toc"],
    "navbar_align": "left",
    "header_links_before_dropdown": 4,
    "navbar_persistent": [],
    "navbar_end": ["search-button", "theme-switcher"],
    "footer_start": ["copyright"],
    "footer_end": ["sphinx-version", "theme-version"],
    "show_prev_next": True,
}
# The left sidebar lists a section's pages: only the gallery has any. The other pages use the full
# width (the navigation bar links them); an empty "Section Navigation" column would only narrow them.
html_sidebars = {"**": [], "gallery/index": ["sidebar-nav-bs"]}
html_sidebars |= {f"gallery/{p.stem}": ["sidebar-nav-bs"] for p in (HERE.parent / "examples").glob("[0-9][0-9]_*.py")}


def _tables_filled(app, ctx, lines):
    """The command line's help texts list the rows of their tables (``{contact_laws}``), filled when shown
    (softimpact.app.options.filled): the reference page fills them too."""
    from softimpact.app.options import filled

    lines[:] = [filled(line) for line in lines]


def setup(app):
    for event in ("sphinx-click-process-description", "sphinx-click-process-options"):
        app.connect(event, _tables_filled)
