"""Sphinx configuration of the topomesh documentation site.

Build (from the repository root, as in the README)::

    .venv/bin/python -m sphinx -W --keep-going -b html docs docs/_build/html

The notebooks in ``notebooks/`` are executed during the build (they are
committed without outputs) and a small gallery is rendered into
``docs/_build/gallery``; both need headless rendering (EGL, Agg), set below.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
sys.path.insert(0, str(DOCS / "_ext"))

# headless rendering for the gallery and the notebook kernels (inherited by them)
os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
os.environ.setdefault("MPLBACKEND", "Agg")

import topomesh  # noqa: E402

project = "topomesh"
author = "the topomesh developers"
copyright = "topomesh developers"
release = version = topomesh.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "myst_nb",
    # MathJax served from the site itself: no CDN, the pages work offline
    "sphinx-mathjax-offline",
    "topomesh_docs",
]

exclude_patterns = ["_build", "_ext", "Thumbs.db", ".DS_Store", "**.ipynb_checkpoints"]
html_theme = "furo"
html_title = f"topomesh {release}"
html_static_path: list[str] = []

# --- API reference: the Rust docstrings (numpydoc style) through autodoc +
# napoleon, signatures from python/topomesh/_core.pyi (topomesh_docs.py)
autodoc_member_order = "groupwise"
autodoc_default_options = {"members": True, "undoc-members": True}
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_ivar = True  # dataclass "Attributes": fields, not duplicate attribute entries
napoleon_use_rtype = False

# --- notebooks (myst-nb): executed at every build, outputs rendered as static
# images (no widget JavaScript, no live 3D viewer; see topomesh_docs.py)
nb_execution_mode = "force"
nb_execution_timeout = 300  # per cell
nb_execution_raise_on_error = True
nb_execution_show_tb = True
nb_execution_in_temp = True  # cells that write files write them elsewhere
nb_ipywidgets_js: dict[str, dict[str, str]] = {}
nb_merge_streams = True
myst_enable_extensions = ["dollarmath", "colon_fence"]
myst_heading_anchors = 3
