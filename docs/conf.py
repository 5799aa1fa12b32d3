"""Sphinx configuration of the guides: Markdown (MyST) pages, a theme that loads nothing from the
network, so the built site works offline (tests/test_docs_site.py builds it strictly)."""

project = "situated"
author = "the situated developers"
extensions = ["myst_parser"]
source_suffix = {".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build"]
# Headings get anchors, so "page.md#section" links are checked like any reference.
myst_heading_anchors = 3
# Shell and JSON examples are shown as written; a block Pygments cannot lex must not fail the build.
highlight_language = "text"
# A console block whose JSON spans lines (a quoted request body) is shown unhighlighted rather than
# failing the strict build: colour is not a broken link or reference.
suppress_warnings = ["misc.highlighting_failure"]
html_theme = "furo"
html_title = "situated"
html_static_path: list[str] = []
# Nothing at view time comes from elsewhere: no search index service, no fonts, no analytics.
html_show_sourcelink = False
