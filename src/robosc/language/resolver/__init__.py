"""Resolution: syntax nodes of a robot (and the libraries it imports) to the checked model.

Order: every file's data types and interfaces; every component's names
(communications, states, variables); then transitions, requirements and
provide statements, which may name anything declared before.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, Protocol

from robosc.language import model as m
from robosc.language import syntax as s
from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, once_per_place
from robosc.language.resolver.components import BehaviourResolver, declare
from robosc.language.resolver.expressions import ExpressionResolver
from robosc.language.resolver.instances import Instance, instances
from robosc.language.resolver.reporter import Reporter
from robosc.language.resolver.scope import FileScope
from robosc.language.resolver.statements import StatementResolver
from robosc.language.resolver.tables import ComponentTables
from robosc.language.source import Span
from robosc.record import field, record

__all__ = ["FileScope", "LibraryProvider", "LibraryUnit", "Reporter", "ResolveResult", "resolve", "scope_of"]

_NOT_AVAILABLE = ""  # lookup answer for a component whose import failed (already reported)


@record(frozen=False)
class LibraryUnit:
    """A parsed library with its data types and interfaces resolved."""

    syntax: s.FileSyntax
    scope: FileScope

    def component(self, name: str) -> s.ComponentSyntax | None:
        return next(
            (
                d
                for d in self.syntax.definitions
                if isinstance(d, (s.LocalComponentSyntax, s.ImportedComponentSyntax)) and d.name.text == name
            ),
            None,
        )

    @property
    def component_names(self) -> list[str]:
        return [
            d.name.text
            for d in self.syntax.definitions
            if isinstance(d, (s.LocalComponentSyntax, s.ImportedComponentSyntax))
        ]


class LibraryProvider(Protocol):
    def find(self, name: s.Name, reporter: Reporter) -> LibraryUnit | None:
        """The library called ``name``, or None after reporting why it cannot be had."""


@record
class ResolveResult:
    model: m.Model
    diagnostics: tuple[Diagnostic, ...]
    # each name that resolved and the model object it names (for editors: definition, references)
    references: tuple[tuple[Span, Any], ...] = field(default=(), compare=False, repr=False)


def scope_of(file: s.FileSyntax, reporter: Reporter) -> FileScope:
    """A file's scope with its data types, interfaces and enum rules resolved."""
    scope = FileScope(file, reporter)
    scope.build_all(ExpressionResolver(reporter, scope.enum_values, lambda _: None, list))
    return scope


@record(frozen=False)
class _Entry:
    syntax: s.LocalComponentSyntax | None  # None when the import failed
    tables: ComponentTables
    scope: FileScope
    span: Span
    library: LibraryUnit | None = None
    library_name: str | None = None
    library_component: str | None = None
    instance: Instance | None = None


class _Resolver:
    def __init__(self, file: s.FileSyntax, libraries: LibraryProvider, sizes: Mapping[str, int]) -> None:
        self.file = file
        self.libraries = libraries
        self.sizes = sizes
        self.reporter = Reporter()
        self.scope = scope_of(file, self.reporter)
        self.entries: dict[str, _Entry] = {}
        self.order: list[_Entry] = []
        self.groups: dict[str, list[str]] = {}  # bot -> [bot1, .., botN]
        self._communications: dict[str, m.Communication] | None = None

    # -- phase 1 -------------------------------------------------------------------
    def declare_components(self) -> None:
        for definition in self.file.definitions:
            if not isinstance(definition, (s.LocalComponentSyntax, s.ImportedComponentSyntax)):
                continue
            declared = instances(definition, self.reporter, self.sizes.get(definition.name.text))
            if definition.instances is not None and definition.instances.count is not None:
                self.groups.setdefault(definition.name.text, [i.name for i in declared])
            unit = None
            if isinstance(definition, s.ImportedComponentSyntax) and declared:
                unit = self.libraries.find(definition.library, self.reporter)
            for instance in declared:
                if isinstance(definition, s.LocalComponentSyntax):
                    tables = declare(definition, instance.name, self.scope, instance, self.reporter)
                    entry = _Entry(definition, tables, self.scope, definition.span, instance=instance)
                else:
                    entry = self._import(definition, unit, instance)
                self._add(instance.name, entry)
        unknown = sorted(set(self.sizes) - set(self.groups))
        if unknown:  # asked for on the command line: said at the model's name
            groups = ", ".join(f"'{g}'" for g in self.groups) or "none"
            self.reporter.error(
                self.file.name.span,
                f"--instances {unknown[0]}=...: '{self.file.name.text}' declares no component '{unknown[0]}' with "
                f"instances (component {unknown[0]}[N]); its groups of instances: {groups}",
                Code.INSTANCES,
            )

    def _add(self, name: str, entry: _Entry) -> None:
        self.order.append(entry)
        self.entries.setdefault(name, entry)

    def _import(self, syntax: s.ImportedComponentSyntax, unit: LibraryUnit | None, instance: Instance) -> _Entry:
        local = instance.name
        failed = _Entry(None, ComponentTables(local), self.scope, syntax.span, instance=instance)
        if unit is None:
            return failed
        found = unit.component(syntax.component.text)
        if found is None:
            self.reporter.unknown(
                syntax.component.span,
                f"component of library '{syntax.library.text}'",
                syntax.component.text,
                unit.component_names,
            )
            return failed
        if not isinstance(found, s.LocalComponentSyntax):
            self.reporter.error(
                syntax.component.span,
                f"'{syntax.component.text}' is itself imported in library '{syntax.library.text}'; "
                "import it from the library that defines it",
                Code.UNKNOWN_NAME,
            )
            return failed
        tables = declare(found, local, unit.scope, instance, self.reporter)
        for communication in tables.communications:
            for data_type in m.data_types_of(communication):
                self.scope.add_imported(data_type)
            if communication.interface is not None and communication.interface not in self.scope.interfaces:
                self.scope.interfaces.append(communication.interface)
        for variable in tables.variables.values():
            self.scope.add_imported(variable.type)
        return _Entry(
            found, tables, unit.scope, syntax.span, unit, syntax.library.text, syntax.component.text, instance
        )

    # -- lookups -------------------------------------------------------------------
    def _robot_component(self, name: str) -> ComponentTables | str | None:
        entry = self.entries.get(name)
        if entry is None:
            return None
        return entry.tables if entry.syntax is not None else _NOT_AVAILABLE

    def _library_component(self, entry: _Entry, name: str) -> ComponentTables | str | None:
        """A component named inside a library component: the robot component that imports it."""
        assert entry.library is not None
        if entry.library.component(name) is None:
            return None
        for other in self.order:
            if other.library is entry.library and other.library_component == name:
                return other.tables
        return f"component '{name}' of library '{entry.library_name}' is not imported into this robot"

    def _communication(self, name: str) -> m.Communication | None:
        if self._communications is None:  # built once every component is declared
            self._communications = {}
            for entry in self.order:
                for communication in entry.tables.communications:
                    self._communications.setdefault(communication.name, communication)
        return self._communications.get(name)

    def _communication_names(self) -> list[str]:
        return [c.name for e in self.order for c in e.tables.communications]

    def _component_names(self) -> list[str]:
        return list(self.entries)

    # -- phase 2 -------------------------------------------------------------------
    def components(self) -> tuple[m.Component, ...]:
        robot_expressions = ExpressionResolver(
            self.reporter, self.scope.enum_values, self._robot_component, self._component_names, self.groups
        )
        built = []
        for entry in self.order:
            expressions = robot_expressions
            if entry.library is not None:
                expressions = ExpressionResolver(
                    self.reporter,
                    entry.scope.enum_values,
                    lambda name, e=entry: self._library_component(e, name),  # type: ignore[misc]
                    lambda e=entry: e.library.component_names,  # type: ignore[misc]
                )
            behaviour = BehaviourResolver(
                entry.tables, expressions, self.reporter, self._communication, self._communication_names
            )
            automata: tuple[m.Automaton, ...] = ()
            if entry.syntax is not None:
                automata = tuple(
                    behaviour.automaton(item) for item in entry.syntax.items if isinstance(item, s.BehaviourSyntax)
                )
            instance = entry.instance
            built.append(
                m.Component(
                    entry.tables.name,
                    tuple(entry.tables.communications),
                    automata,
                    entry.span,
                    entry.library_name,
                    entry.library_component,
                    instance.group if instance else None,
                    instance.index if instance else None,
                    instance.namespace if instance else None,
                )
            )
        return tuple(built)

    def statements(self) -> tuple[tuple[m.Requirement, ...], tuple[m.Provide, ...]]:
        expressions = ExpressionResolver(
            self.reporter, self.scope.enum_values, self._robot_component, self._component_names, self.groups
        )
        resolver = StatementResolver(expressions, self.reporter, self._communication, self._communication_names)
        requirements: list[m.Requirement] = []
        provides: list[m.Provide] = []
        for definition in self.file.definitions:
            if isinstance(definition, (s.RequirementSyntax, s.ProvideSyntax, s.ForEachSyntax)):
                resolver.statement(definition, requirements, provides)
        return tuple(requirements), tuple(provides)


def resolve(
    file: s.FileSyntax, path: str, libraries: LibraryProvider, sizes: Mapping[str, int] | None = None
) -> ResolveResult:
    """Resolve a parsed robot or library; unresolvable parts are reported and left out.
    ``sizes``: how many instances a ``component NAME[N]`` has instead of N, by NAME."""
    resolver = _Resolver(file, libraries, sizes or {})
    resolver.declare_components()
    components = resolver.components()
    requirements, provides = resolver.statements()
    model = m.Model(
        file.kind,
        file.name.text,
        path,
        components,
        tuple(resolver.scope.data_types),
        tuple(resolver.scope.interfaces),
        requirements,
        provides,
        file.name.span,
    )
    unique = once_per_place(resolver.reporter.diagnostics)
    # a component named in an expression was referred to by its tables: name the component
    built = {id(entry.tables): component for entry, component in zip(resolver.order, components, strict=True)}
    references = tuple((span, built.get(id(target), target)) for span, target in resolver.reporter.references)
    return ResolveResult(model, unique, references)
