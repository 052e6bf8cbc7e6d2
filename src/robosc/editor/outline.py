"""The outline of a model file (LSP document symbols) from its syntax tree, so that it is
there while the model still has errors, as long as it parses."""

from __future__ import annotations

from lsprotocol import types as lsp

from robosc.editor.positions import to_range
from robosc.language import syntax as s
from robosc.language.source import Span

Kind = lsp.SymbolKind


def outline(tree: s.FileSyntax, lines: list[str]) -> list[lsp.DocumentSymbol]:
    def symbol(name: str, kind: lsp.SymbolKind, span: Span, name_span: Span, detail: str = "", children=()):  # type: ignore[no-untyped-def]
        whole, selected = to_range(span, lines), to_range(name_span, lines)
        return lsp.DocumentSymbol(
            name=name, kind=kind, range=whole, selection_range=selected, detail=detail or None, children=list(children)
        )

    def counted(d: s.LocalComponentSyntax | s.ImportedComponentSyntax, detail: str) -> str:
        count = d.instances.count if d.instances is not None else None
        return f"{detail}, {count.value} instances" if count is not None else detail

    def statements(definitions: tuple[s.Definition, ...] | tuple[s.Definition | s.ForEachSyntax, ...]) -> list:  # type: ignore[type-arg]
        found = []
        for d in definitions:
            if isinstance(d, s.RequirementSyntax):
                names = ", ".join(n.text for n in d.events.names)
                found.append(symbol(f"requirement {names} {d.kind}", Kind.Property, d.span, d.events.span))
            elif isinstance(d, s.ProvideSyntax):
                found.append(symbol(f"provide {d.communication.text}", Kind.Constant, d.span, d.communication.span))
            elif isinstance(d, s.ForEachSyntax):
                title = f"for {d.binder.text} in {d.group.text}"
                found.append(symbol(title, Kind.Namespace, d.span, d.binder.span, "", statements(d.items)))
        return found

    out = []
    for d in tree.definitions:
        if isinstance(d, s.LocalComponentSyntax):
            children = []
            for item in d.items:
                if isinstance(item, s.BehaviourSyntax):
                    for b in item.items:
                        if isinstance(b, s.StateSyntax):
                            children.append(symbol(b.name.text, Kind.Enum, b.span, b.name.span, "state"))
                        elif isinstance(b, s.VariableSyntax):
                            children.append(symbol(b.name.text, Kind.Variable, b.span, b.name.span, "variable"))
                else:
                    kind = type(item).__name__.removesuffix("Syntax").lower()
                    children.append(symbol(item.name.text, Kind.Event, item.span, item.name.span, kind))
            out.append(symbol(d.name.text, Kind.Class, d.span, d.name.span, counted(d, "component"), children))
        elif isinstance(d, s.ImportedComponentSyntax):
            detail = f"from {d.library.text}.{d.component.text}"
            out.append(symbol(d.name.text, Kind.Class, d.span, d.name.span, counted(d, detail)))
        elif isinstance(d, (s.RequirementSyntax, s.ProvideSyntax, s.ForEachSyntax)):
            out += statements((d,))
        elif isinstance(d, s.ObjectTypeSyntax | s.EnumTypeSyntax):
            shape = Kind.Struct if isinstance(d, s.ObjectTypeSyntax) else Kind.Enum
            out.append(symbol(d.name.text, shape, d.span, d.name.span, "datatype"))
        elif isinstance(d, s.InterfaceSyntax):
            out.append(symbol(d.name.text, Kind.Interface, d.span, d.name.span, "interface"))
    return out


def folds(tree: s.FileSyntax) -> list[lsp.FoldingRange]:
    """A folding range for every definition, behaviour and state that spans lines."""
    spans: list[Span] = []
    for d in tree.definitions:
        spans.append(d.span)
        if isinstance(d, s.ForEachSyntax):
            spans += [i.span for i in d.items]
        if isinstance(d, s.LocalComponentSyntax):
            for item in d.items:
                if isinstance(item, s.BehaviourSyntax):
                    spans.append(item.span)
                    spans += [b.span for b in item.items if isinstance(b, s.StateSyntax)]
    return [
        lsp.FoldingRange(start_line=span.line - 1, end_line=span.end_line - 1)
        for span in spans
        if span.end_line > span.line
    ]
