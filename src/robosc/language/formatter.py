"""``robosc fmt``: a parsed file printed in one canonical layout, comments kept.

Comments are placed by position: those before an item (or inside a one-line
item) go on their own lines above it, one that follows an item on the same
line stays at the end of that line, and those before a closing brace stay
inside the block.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence

from robosc.language import syntax as s
from robosc.language.keywords import escape_name
from robosc.language.source import Span

INDENT = "    "


# ---- expressions and types (one line each) ----------------------------------


def name(n: s.Name | s.QualifiedName) -> str:
    if isinstance(n, s.QualifiedName):
        return f"{escape_name(n.instance.text)}.{escape_name(n.name.text)}"
    return escape_name(n.text)


def instances(i: s.Instances | None) -> str:
    """``[4] namespace "/fleet" initial a, b, c, d`` after a component's name."""
    if i is None:
        return ""
    text = f"[{i.count.value}]" if i.count is not None else ""
    if i.namespace is not None:
        text += f" namespace {i.namespace.raw}"
    if i.initial:
        text += " initial " + ", ".join(name(n) for n in i.initial)
    return text


def expr(e: s.Expr) -> str:
    if isinstance(e, s.Binary):
        return f"{expr(e.left)} {e.op} {expr(e.right)}"
    if isinstance(e, s.Unary):
        return f"{e.op}{expr(e.operand)}"
    if isinstance(e, s.Paren):
        return f"({expr(e.inner)})"
    if isinstance(e, s.IntLit):
        return str(e.value)
    if isinstance(e, s.DoubleLit):
        return e.text
    if isinstance(e, s.StrLit):
        return e.raw
    if isinstance(e, s.BoolLit):
        return "true" if e.value else "false"
    if isinstance(e, s.Quantifier):
        return f"{e.kind.text}({name(e.binder)} in {name(e.group)}: {expr(e.body)})"
    if isinstance(e, s.Call):
        return f"{e.kind.text}({', '.join(expr(a) for a in e.args)})"
    head = "value" if e.head is None else name(e.head)
    return head + "".join(f"[{st.index}]" if isinstance(st, s.IndexStep) else f".{name(st.name)}" for st in e.steps)


def data_type(t: s.TypeSyntax) -> str:
    if isinstance(t, s.BasicTypeSyntax):
        return f"integer({t.low}..{t.high})" if t.low is not None else t.kind
    if isinstance(t, s.ArrayTypeSyntax):
        return f"array({data_type(t.element)})"
    return name(t.name)


def object_value(v: s.ObjectValueSyntax | s.Expr) -> str:
    if not isinstance(v, s.ObjectValueSyntax):
        return expr(v)
    if not v.fields:
        return "{}"
    return "{ " + ", ".join(f"{name(f.name)}: {object_value(f.value)}" for f in v.fields) + " }"


def events(e: s.EventsSyntax) -> str:
    return "{" + ", ".join(name(n) for n in e.names) + "}" if e.is_set else name(e.names[0])


def _with(identifier: s.StrLit | None, parts: list[str], links: s.Name | None) -> str:
    head = [f"identifier: {identifier.raw}"] if identifier is not None else []
    tail = f" links {name(links)}" if links is not None else ""
    return ", ".join(head + parts) + tail


def one_line(item: object) -> str:
    """The text of an item that is printed on one line."""
    if isinstance(item, s.MessageSyntax):
        rest = _with(item.identifier, [f"type: {data_type(item.type)}"], item.links)
        return f"{item.direction} message {name(item.name)} with {rest}"
    if isinstance(item, s.ServiceSyntax):
        parts = [f"request: {data_type(item.request)}", f"response: {data_type(item.response)}"]
        return f"service {name(item.name)} with {_with(item.identifier, parts, item.links)}"
    if isinstance(item, s.ActionSyntax):
        parts = [
            f"request: {data_type(item.request)}",
            f"response: {data_type(item.response)}",
            f"feedback: {data_type(item.feedback)}",
        ]
        return f"action {name(item.name)} with {_with(item.identifier, parts, item.links)}"
    if isinstance(item, s.VariableSyntax):
        initial = f" = {expr(item.initial)}" if item.initial is not None else ""
        return f"variable {name(item.name)}: {data_type(item.type)}{initial}"
    if isinstance(item, s.ResultTransitionSyntax):
        text = f"on {item.result} {item.preposition} {name(item.communication)}"
        if item.assignments:
            text += " do " + ", ".join(f"{expr(a.target)} := {expr(a.value)}" for a in item.assignments)
        return text + (f" goto {name(item.target)}" if item.target is not None else "")
    if isinstance(item, s.TauTransitionSyntax):
        text = "transition"
        text += f" if {expr(item.guard)}" if item.guard is not None else ""
        return text + (f" goto {name(item.target)}" if item.target is not None else "")
    if isinstance(item, s.PropertySyntax):
        return f"{name(item.name)}: {data_type(item.type)}"
    if isinstance(item, s.EnumRuleSyntax):
        condition = "default" if item.condition is None else expr(item.condition)
        return f"{condition} -> {name(item.value)}"
    if isinstance(item, s.InterfaceSyntax):
        return f"interface {name(item.name)} use {name(item.ros_type)} from {name(item.package)}"
    if isinstance(item, s.ImportedComponentSyntax):
        count = f"[{item.instances.count.value}]" if item.instances and item.instances.count else ""
        options = instances(item.instances).removeprefix(count)
        return f"component {name(item.name)}{count} from {name(item.library)} import {name(item.component)}{options}"
    if isinstance(item, s.RequirementSyntax):
        if item.kind == "needs":
            return f"requirement {events(item.events)} needs {expr(item.condition)}"
        return f"requirement {expr(item.condition)} disables {events(item.events)}"
    if isinstance(item, s.ProvideSyntax):
        condition = f" if {expr(item.condition)}" if item.condition is not None else ""
        return f"provide {name(item.communication)} with {object_value(item.data)}{condition}"
    raise TypeError(f"not a one-line item: {type(item).__name__}")


# ---- layout with comments ---------------------------------------------------


class _Printer:
    def __init__(self, comments: tuple[s.Comment, ...]) -> None:
        self.comments = sorted(comments, key=lambda c: c.span.start)
        self.next = 0
        self.lines: list[str] = []

    def _comments_before(self, pos: int, depth: int) -> None:
        while self.next < len(self.comments) and self.comments[self.next].span.start < pos:
            self.lines.append(INDENT * depth + self.comments[self.next].text)
            self.next += 1

    def _trailing(self, span: Span) -> str:
        if self.next < len(self.comments):
            comment = self.comments[self.next]
            if comment.span.line == span.end_line and comment.span.start >= span.end:
                self.next += 1
                return " " + comment.text
        return ""

    def _has_comment_inside(self, span: Span) -> bool:
        return self.next < len(self.comments) and self.comments[self.next].span.start < span.end

    def blank(self) -> None:
        if self.lines and self.lines[-1] != "":
            self.lines.append("")

    def leaf(self, text: str, span: Span, depth: int) -> None:
        self._comments_before(span.end, depth)
        self.lines.append(INDENT * depth + text + self._trailing(span))

    def block(self, header: str, span: Span, depth: int, body: Sequence[tuple[object, str]]) -> None:
        """``header { body }``; ``body`` pairs each child with its group name (a blank
        line separates children of different groups, and blocks from everything)."""
        self._comments_before(span.start, depth)
        if not body and not self._has_comment_inside(span):
            self.lines.append(INDENT * depth + header + " {}" + self._trailing(span))
            return
        self.lines.append(INDENT * depth + header + " {")
        previous = None
        for child, group in body:
            if previous is not None and (group != previous or group == "block"):
                self.blank()
            self.item(child, depth + 1)
            previous = group
        self._comments_before(span.end, depth + 1)
        self.lines.append(INDENT * depth + "}" + self._trailing(span))

    def item(self, node: object, depth: int) -> None:
        body: list[tuple[object, str]]
        if isinstance(node, s.LocalComponentSyntax):
            body = [(i, "block" if isinstance(i, s.BehaviourSyntax) else "communication") for i in node.items]
            self.block(f"component {name(node.name)}{instances(node.instances)}", node.span, depth, body)
        elif isinstance(node, s.ForEachSyntax):
            body = [(i, "block" if isinstance(i, s.ForEachSyntax) else type(i).__name__) for i in node.items]
            self.block(f"for {name(node.binder)} in {name(node.group)}", node.span, depth, body)
        elif isinstance(node, s.BehaviourSyntax):
            groups = {s.VariableSyntax: "variable", s.StateSyntax: "block"}
            body = [(i, groups.get(type(i), "transition")) for i in node.items]
            self.block("behaviour", node.span, depth, body)
        elif isinstance(node, s.StateSyntax):
            flags = ("initial " if node.initial else "") + ("marked " if node.marked else "")
            body = [(t, "transition") for t in node.transitions]
            self.block(f"{flags}state {name(node.name)}", node.span, depth, body)
        elif isinstance(node, s.ObjectTypeSyntax):
            body = [(p, "property") for p in node.properties]
            self.block(f"datatype object {name(node.name)}", node.span, depth, body)
        elif isinstance(node, s.EnumTypeSyntax):
            body = [(r, "rule") for r in node.rules]
            header = f"datatype enum {name(node.name)} from {data_type(node.source)} to"
            self.block(header, node.span, depth, body)
        else:
            self.leaf(one_line(node), node.span, depth)  # type: ignore[attr-defined]


def _group(definition: s.Definition) -> str:
    if isinstance(definition, (s.LocalComponentSyntax, s.ObjectTypeSyntax, s.EnumTypeSyntax, s.ForEachSyntax)):
        return "block"
    return type(definition).__name__


def format_syntax(file: s.FileSyntax) -> str:
    """The canonical text of a parsed file."""
    printer = _Printer(file.comments)
    body = [(d, _group(d)) for d in file.definitions]
    printer.block(f"{file.kind} {name(file.name)}", file.span, 0, body)
    printer._comments_before(sys.maxsize, 0)
    return "\n".join(printer.lines) + "\n"
