"""MkDocs hook: the check codes page is made from robosc's own registry of codes
(``robosc.language.codes``) and one small model per code in ``docs/rules/``, so that the page
lists every code robosc has, with a model that the tests check triggers it."""

from __future__ import annotations

from pathlib import Path
from typing import Any

RULES = Path(__file__).parent / "rules"
MARKER = "<!-- codes -->"


def codes_markdown() -> str:
    from robosc.language.codes import Code

    parts = []
    for code in Code:
        parts.append(f"### `{code.value}`\n\n{code.description[0].upper()}{code.description[1:]}.\n")
        example = RULES / f"{code.value}.rscd"
        if example.exists():
            parts.append(f"```robosc\n{example.read_text().rstrip()}\n```\n")
    return "\n".join(parts)


def on_page_markdown(markdown: str, page: Any, **kwargs: Any) -> str:
    if MARKER in markdown:
        return markdown.replace(MARKER, codes_markdown())
    return markdown


def on_page_content(html: str, page: Any, **kwargs: Any) -> str:
    """mkdocs-click shows click 8.3's marker for "no default" as its name: shown as nothing."""
    return html.replace("<code>Sentinel.UNSET</code>", "").replace("Sentinel.UNSET", "")
