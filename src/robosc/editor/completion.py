"""Completion in context, from the text before the cursor and the last model that checked:
states after ``goto``, a component's communications after ``on response from`` / ``on request
to``, a component's states and variables after ``Component.``, enum values after ``=`` (and
after ``:=``), else keywords and the names in scope."""

from __future__ import annotations

import re

from lsprotocol import types as lsp

from robosc.language import model as m
from robosc.language.keywords import KEYWORDS, escape_name

Kind = lsp.CompletionItemKind
COMPONENT = re.compile(r"\bcomponent\s+\^?([A-Za-z_]\w*)")


def _component_at(text_before: str, model: m.Model) -> m.Component | None:
    """The component whose declaration comes last before the cursor."""
    names = COMPONENT.findall(text_before)
    if not names:
        return None
    return next((c for c in model.components if c.name == names[-1]), None)


def _item(name: str, kind: lsp.CompletionItemKind, detail: str = "") -> lsp.CompletionItem:
    return lsp.CompletionItem(label=name, kind=kind, detail=detail or None, insert_text=escape_name(name))


def _enum_values(model: m.Model) -> list[lsp.CompletionItem]:
    return [
        _item(v.name, Kind.EnumMember, t.name)
        for t in model.data_types
        if isinstance(t, m.EnumType)
        for v in t.values
    ]


def complete(text_before: str, model: m.Model | None) -> list[lsp.CompletionItem]:
    """``text_before``: the document up to the cursor; ``model``: the last one that checked."""
    line = text_before.rsplit("\n", 1)[-1]
    words = [_item(k, Kind.Keyword) for k in sorted(KEYWORDS)]
    if model is None:
        return words
    own = _component_at(text_before, model)
    automaton = own.automaton if own is not None else None
    if re.search(r"\bgoto\s+\^?\w*$", line):
        return [_item(s.name, Kind.Enum, "state") for s in automaton.states] if automaton else []
    if re.search(r"\bon\s+(response\s+from|request\s+to|error\s+from|feedback\s+from|cancel\s+to)\s+\^?\w*$", line):
        return [_item(c.name, Kind.Event, type(c).__name__.lower()) for c in own.communications] if own else []
    member = re.search(r"\b([A-Za-z_]\w*)\.\w*$", line)
    if member is not None:
        component = next((c for c in model.components if c.name == member.group(1)), None)
        if component is None or component.automaton is None:
            return []
        states = [_item(s.name, Kind.Enum, "state") for s in component.automaton.states]
        return states + [_item(v.name, Kind.Variable, "variable") for v in component.automaton.variables]
    if re.search(r"(:?=|!=)\s*\^?\w*$", line):
        return _enum_values(model)
    names = [_item(c.name, Kind.Class, "component") for c in model.components]
    names += [_item(c.name, Kind.Event, type(c).__name__.lower()) for c in model.communications]
    if automaton is not None:
        names += [_item(v.name, Kind.Variable, "variable") for v in automaton.variables]
    names += [_item(t.name, Kind.Struct, "datatype") for t in model.data_types]
    return words + names + _enum_values(model)
