# Sphinx configuration for the FRICTION-EQ documentation (LAMMPS format).
#   sphinx-build -W -b html doc/src doc/html -c doc
# Code blocks use LAMMPS' own Pygments lexer when the LAMMPS tree is known
# (environment variable LAMMPS_DIR, else the trees ./friction-eq fetches into
# .cache/lammps-<version>); :doc: references to LAMMPS pages that are not
# part of this package resolve to docs.lammps.org.
import os
import sys
from pathlib import Path

from docutils import nodes

project = "FRICTION-EQ"
author = "FRICTION-EQ developers"
extensions = ["sphinx.ext.mathjax"]
exclude_patterns = []
html_theme = "alabaster"
html_static_path = []
root = Path(__file__).resolve().parents[1]
if os.environ.get("LAMMPS_DIR"):
    lammps = Path(os.environ["LAMMPS_DIR"])
else:
    lammps = next((root / ".cache" / d for d in ("lammps-2026", "lammps-2025", "lammps-2021", "lammps")
                   if (root / ".cache" / d / "doc").is_dir()), root / ".cache" / "lammps")
lexer_dir = lammps / "doc" / "utils" / "sphinx-config"
if (lexer_dir / "LAMMPSLexer.py").exists():
    sys.path.insert(0, str(lexer_dir))
    from LAMMPSLexer import LAMMPSLexer
    from sphinx.highlighting import lexers
    lexers["LAMMPS"] = LAMMPSLexer(startinline=True)
else:
    from sphinx.highlighting import lexers
    from pygments.lexers.special import TextLexer
    lexers["LAMMPS"] = TextLexer()


def lammps_doc_link(app, env, node, contnode):
    """:doc:`fix_move` etc. that are not pages of this package -> docs.lammps.org"""
    if node.get("reftype") != "doc":
        return None
    target = node["reftarget"].strip("/")
    uri = f"https://docs.lammps.org/{target}.html"
    ref = nodes.reference("", "", internal=False, refuri=uri)
    ref += contnode
    return ref


def setup(app):
    app.connect("missing-reference", lammps_doc_link)
