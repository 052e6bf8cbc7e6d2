"""Completion in context, from the text before the cursor and the last model that checked:
states after ``goto``, a component's communications after ``on response from`` / ``on request
to``, a component's states and variables after ``Component.`` (and, for an instance or an
instance variable such as ``r`` in ``for r in bot``, its communications), groups after ``in``,
enum values after ``=`` (and after ``:=``), else keywords and the names in scope."""

from __future__ import annotations

import re

from lsprotocol import types as lsp

from robosc.language import model as m
from robosc.language.keywords import KEYWORDS, escape_name

Kind = lsp.CompletionItemKind
COMPONENT = re.compile(r"\bcomponent\s+\^?([A-Za-z_]\w*)")
BINDER = re.compile(r"\b([A-Za-z_]\w*)\s+in\s+([A-Za-z_]\w*)")  # `for r in bot`, `all(q in bot: ...`
SOFT = ["for", "in", "namespace", "all", "any", "count"]  # words that are keywords only in place


def _component_at(text_before: str, model: m.Model) -> m.Component | None:
    """The component whose declaration comes last before the cursor (of a group: its first instance)."""
    names = COMPONENT.findall(text_before)
    if not names:
        return None
    return next((c for c in model.components if c.name == names[-1] or c.group == names[-1]), None)


def _local(name: str) -> str:
    """A communication's name as its own component writes it: ``go`` for ``bot1.go``."""
    return name.rsplit(".", 1)[-1]


def _named(name: str, text_before: str, model: m.Model) -> m.Component | None:
    """The component that ``name.`` refers to: a component, an instance, or an instance
    variable bound before the cursor (its group's first instance)."""
    found = next((c for c in model.components if c.name == name), None)
    if found is not None:
        return found
    groups = model.groups
    bound = [group for binder, group in BINDER.findall(text_before) if binder == name and group in groups]
    return groups[bound[-1]][0] if bound else None


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
        return [_item(_local(c.name), Kind.Event, type(c).__name__.lower()) for c in own.communications] if own else []
    if re.search(r"\b[A-Za-z_]\w*\s+in\s+\w*$", line):
        return [_item(g, Kind.Module, f"group of {len(i)} instances") for g, i in model.groups.items()]
    member = re.search(r"\b([A-Za-z_]\w*)\.\w*$", line)
    if member is not None:
        component = _named(member.group(1), text_before, model)
        if component is None:
            return []
        found = []
        if component.group is not None:  # `bot1.go`, `r.go`: an instance's communications
            found += [_item(_local(c.name), Kind.Event, type(c).__name__.lower()) for c in component.communications]
        if component.automaton is not None:
            found += [_item(s.name, Kind.Enum, "state") for s in component.automaton.states]
            found += [_item(v.name, Kind.Variable, "variable") for v in component.automaton.variables]
        return found
    if re.search(r"(:?=|!=)\s*\^?\w*$", line):
        return _enum_values(model)
    words += [_item(k, Kind.Keyword) for k in SOFT]
    names = [_item(c.name, Kind.Class, "component" if c.group is None else "instance") for c in model.components]
    names += [_item(g, Kind.Module, f"group of {len(i)} instances") for g, i in model.groups.items()]
    names += [_item(c.name, Kind.Event, type(c).__name__.lower()) for c in model.communications]
    if automaton is not None:
        names += [_item(v.name, Kind.Variable, "variable") for v in automaton.variables]
    names += [_item(t.name, Kind.Struct, "datatype") for t in model.data_types]
    return words + names + _enum_values(model)
