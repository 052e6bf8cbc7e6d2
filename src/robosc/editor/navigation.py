"""Go to definition, find references and rename, from the names the resolver resolved
(``CheckResult.references``: each name's span and the model object it names) and the
declarations of the checked model."""

from __future__ import annotations

import re
from collections import Counter
from collections.abc import Iterable
from typing import Any

from lsprotocol import types as lsp
from pygls.uris import from_fs_path

from robosc.editor.positions import to_range
from robosc.language import model as m
from robosc.language.keywords import KEYWORDS, escape_name
from robosc.language.source import SourceFile, Span

NAME = re.compile(r"\^?[A-Za-z_][A-Za-z0-9_]*")
WHOLE_NAME = re.compile(r"\^?[A-Za-z_][A-Za-z0-9_]*\Z")


class RenameError(Exception):
    """A rename that cannot be made; the message says why."""


def _contains(span: Span, line: int, character: int) -> bool:
    """Whether a span holds an LSP position (lines from 0; characters as columns from 0)."""
    start, end = (span.line - 1, span.column - 1), (span.end_line - 1, span.end_column - 1)
    return start <= (line, character) <= end


def declarations(model: m.Model | None) -> list[Any]:
    """Every named declaration of a checked model (also those nothing refers to)."""
    if model is None:
        return []
    found: list[Any] = [*model.interfaces]
    for data_type in model.data_types:
        found.append(data_type)
        found += getattr(data_type, "properties", ())
        found += getattr(data_type, "values", ())
    for component in model.components:
        found.append(component)
        found += component.communications
        for automaton in component.behaviours:
            found += automaton.states
            found += automaton.variables
    return found


def same(found: Any, target: Any) -> bool:
    """Whether ``found`` is ``target``'s declaration: itself, or the same declaration in another
    instance of its component (``bot2.go`` for ``bot1.go``: one text, one rename)."""
    return found is target or (
        type(found) is type(target)
        and not isinstance(target, m.Component)
        and getattr(found, "span", None) == getattr(target, "span", 0)
    )


class Index:
    """The references of one check of one file, and the texts of the files it read."""

    def __init__(
        self,
        path: str,
        references: tuple[tuple[Span, Any], ...],
        sources: dict[str, SourceFile],
        declared: Iterable[Any] = (),
        errors: Counter[str] | None = None,
    ) -> None:
        self.path = path
        self.references = references
        self.errors = errors if errors is not None else Counter()  # error code -> how many the check found
        self.texts = {p: source.text for p, source in sources.items()}
        self.lines = {p: text.splitlines() for p, text in self.texts.items()}
        targets = {id(t): t for t in declared}
        targets.update((id(t), t) for _, t in references)
        self.targets = [t for t in targets.values() if isinstance(getattr(t, "span", None), Span)]

    def location(self, span: Span) -> lsp.Location:
        return lsp.Location(uri=from_fs_path(span.path) or span.path, range=to_range(span, self.lines.get(span.path, [])))

    def name_span(self, target: Any) -> Span | None:
        """Where a declaration writes its name: the first word of its text that is the name
        (a keyword only with its ``^``; an instance's communication ``bot1.go`` writes ``go``)."""
        span, name = target.span, getattr(target, "name", None)
        text = self.texts.get(span.path)
        if text is None or not isinstance(name, str):
            return None
        if isinstance(target, m.Component) and target.group is not None:
            return None  # an instance is named by its group and number: nowhere written whole
        name = name.rsplit(".", 1)[-1]
        for match in NAME.finditer(text, span.start, span.end):
            word = match.group()
            if word.lstrip("^") == name and (word.startswith("^") or name not in KEYWORDS):
                return Span.of(span.path, text, match.start(), match.end())
        return None

    def target_at(self, position: lsp.Position) -> Any:
        """The model object named at ``position``: a use of it, else its declaration."""
        line, character = position.line, position.character
        for span, target in self.references:
            if span.path == self.path and _contains(span, line, character):
                return target
        declared = [t for t in self.targets if t.span.path == self.path and _contains(t.span, line, character)]
        # the innermost declaration (a state inside a component's span, say)
        return min(declared, key=lambda t: (t.span.end - t.span.start), default=None)

    def name_at(self, position: lsp.Position) -> tuple[Any, Span] | None:
        """The model object whose name is written at ``position``, and that name's span."""
        line, character = position.line, position.character
        for span, target in self.references:
            if span.path == self.path and _contains(span, line, character):
                return target, span
        for target in self.targets:
            if target.span.path == self.path and _contains(target.span, line, character):
                written = self.name_span(target)
                if written is not None and _contains(written, line, character):
                    return target, written
        return None

    def definition(self, position: lsp.Position) -> lsp.Location | None:
        target = self.target_at(position)
        return self.location(self.name_span(target) or target.span) if target is not None else None

    def uses(self, position: lsp.Position, declaration: bool) -> list[lsp.Location]:
        target = self.target_at(position)
        if target is None:
            return []
        spans = dict.fromkeys(span for span, t in self.references if same(t, target))  # instances share theirs
        found = [self.location(span) for span in spans]
        if declaration:
            found.insert(0, self.location(self.name_span(target) or target.span))
        return found

    def rename(self, position: lsp.Position, new_name: str) -> dict[str, list[tuple[Span, str]]]:
        """path -> (span, new text) of every place that writes the name at ``position``:
        its declaration and each use, the new name ``^``-escaped where it is a keyword."""
        found = self.name_at(position)
        if found is None:
            raise RenameError("no name to rename here")
        target, _ = found
        if isinstance(target, m.Component) and target.group is not None:
            raise RenameError(
                f"'{target.name}' is instance {target.index} of '{target.group}': rename the group where it is declared"
            )
        if WHOLE_NAME.match(new_name) is None:
            raise RenameError(f"'{new_name}' is not a name: a letter or '_', then letters, digits or '_'")
        text = escape_name(new_name.lstrip("^"))
        declared = self.name_span(target)
        spans = [span for span, t in self.references if same(t, target)]
        if declared is not None:
            spans.insert(0, declared)
        edits: dict[str, list[tuple[Span, str]]] = {}
        for span in dict.fromkeys(spans):
            edits.setdefault(span.path, []).append((span, text))
        kept = self._keep_ros_name(target, declared)
        if kept is not None:
            edits.setdefault(kept[0].path, []).append(kept)
        return edits

    def _keep_ros_name(self, target: Any, declared: Span | None) -> tuple[Span, str] | None:
        """A communication without an identifier is on the ROS graph under its name: renamed,
        it keeps that ROS name by gaining ``identifier: "<old name>",`` after its ``with``."""
        if not isinstance(target, (m.Message, m.Service, m.Action)) or declared is None:
            return None
        text = self.texts[declared.path]
        if target.identifier is not None and (
            "." not in target.name or re.search(r"\bidentifier:", text[declared.end : target.span.end])
        ):
            return None  # its ROS name is written (an instance's has its namespace whether written or not)
        found = re.compile(r"\bwith\b[ \t]*").search(text, declared.end, target.span.end)
        if found is None:
            return None
        return Span.of(declared.path, text, found.end()), f'identifier: "{target.name.rsplit(".", 1)[-1]}", '
