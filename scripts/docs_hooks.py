"""MkDocs hook (mkdocs.yml ``hooks:``): the docstrings' reST markup rendered, never shown raw.

The package's docstrings follow numpydoc and cite with Sphinx roles (``:func:`estimate```,
``:math:`u^2```) and ``.. math::`` blocks; mkdocstrings renders docstrings as Markdown, in
which these stay literal text. After each page is rendered, :func:`on_page_content` turns

- a cross-reference role ``:func:/:class:/:meth:/:mod:/:data:/:attr:/:obj:/:exc:`` around
  inline code into the code alone (``~a.b.c`` shows ``c``, as Sphinx does);
- ``:math:`x``` into inline math and a ``.. math::`` paragraph into display math, both
  typeset by MathJax (``pymdownx.arithmatex`` in generic mode, mkdocs.yml).

``tests/test_docs_site.py`` builds the site and fails on any raw role or directive left.
"""

from __future__ import annotations

import re

_ROLE = re.compile(r":(?:func|class|meth|mod|data|attr|obj|exc|py:\w+):<code>(~?)([^<]*)</code>")
_MATH = re.compile(r":math:<code>([^<]*)</code>")
_BLOCK = re.compile(r"<p>\.\. math::\s*(.*?)</p>", re.S)


def _role(m: re.Match) -> str:
    name = m.group(2)
    return f"<code>{name.rsplit('.', 1)[-1] if m.group(1) else name}</code>"


def render_rest(html: str) -> str:
    """The page's HTML with the reST roles and math directives rendered (module docstring)."""
    html = _ROLE.sub(_role, html)
    html = _MATH.sub(lambda m: f'<span class="arithmatex">\\({m.group(1)}\\)</span>', html)
    return _BLOCK.sub(lambda m: f'<div class="arithmatex">\\[{m.group(1).strip()}\\]</div>',
                      html)


def on_page_content(html, **kwargs):
    return render_rest(html)
