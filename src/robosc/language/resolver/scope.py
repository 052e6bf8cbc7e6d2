"""What one file defines: data types, interfaces and enum values, built on demand.

Data types may refer to types defined further down, so each is built the first
time it is asked for. Enum rules are filled in after every type exists (their
conditions may name any enum's values); that is the one place where a model
object is completed after construction, and it happens before anyone else sees it.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from robosc.language import model as m
from robosc.language import syntax as s
from robosc.language.codes import Code
from robosc.language.resolver.reporter import Reporter

if TYPE_CHECKING:
    from robosc.language.resolver.expressions import ExpressionResolver

NamedTypeSyntax = s.ObjectTypeSyntax | s.EnumTypeSyntax


# other languages' and ROS's names for RoboSC's basic types (a basic type is sent as the
# std_msgs message of the same kind: boolean as Bool, integer as Int32, double as Float32)
_FOREIGN = {
    "boolean": ("bool", "Bool"),
    "integer": ("int", "Int", "long", "short", "int8", "int16", "int32", "int64", "uint8", "uint16", "uint32",
                "uint64", "Integer"),
    "double": ("float", "Float", "float32", "float64", "real", "number", "Double"),
    "string": ("str", "String", "text", "char", "std::string"),
    "none": ("void", "None", "null", "nil", "Empty", "unit", "nothing"),
}
FOREIGN_TYPES = {alias.lower(): word for word, aliases in _FOREIGN.items() for alias in aliases}


class FileScope:
    """The definitions of one file (robot or library), resolved against that file only."""

    def __init__(self, file: s.FileSyntax, reporter: Reporter) -> None:
        self.file = file
        self.reporter = reporter
        self.type_syntax: dict[str, NamedTypeSyntax] = {}
        self.interface_syntax: dict[str, s.InterfaceSyntax] = {}
        for definition in file.definitions:
            if isinstance(definition, (s.ObjectTypeSyntax, s.EnumTypeSyntax)):
                self.type_syntax.setdefault(definition.name.text, definition)
            elif isinstance(definition, s.InterfaceSyntax):
                self.interface_syntax.setdefault(definition.name.text, definition)
        self._built: dict[int, m.ObjectType | m.EnumType | m.ErrorType] = {}
        self._building: set[int] = set()
        self._interfaces: dict[int, m.Interface] = {}
        # Filled by build_all():
        self.data_types: list[m.ObjectType | m.EnumType] = []
        self.interfaces: list[m.Interface] = []
        self.enum_values: dict[str, tuple[m.EnumType, m.EnumValue]] = {}

    # -- interfaces -------------------------------------------------------------
    def interface(self, syntax: s.InterfaceSyntax) -> m.Interface:
        if id(syntax) not in self._interfaces:
            self._interfaces[id(syntax)] = m.Interface(
                syntax.name.text, syntax.ros_type.text, syntax.package.text, syntax.span
            )
        return self._interfaces[id(syntax)]

    def lookup_interface(self, name: s.Name) -> m.Interface | None:
        syntax = self.interface_syntax.get(name.text)
        if syntax is None:
            self.reporter.unknown(name.span, "interface", name.text, self.interface_syntax)
            return None
        found = self.interface(syntax)
        self.reporter.refer(name.span, found)
        return found

    # -- data types ---------------------------------------------------------------
    def data_type(self, syntax: s.TypeSyntax) -> m.DataType:
        if isinstance(syntax, s.BasicTypeSyntax):
            kind = m.BasicKind(syntax.kind)
            if syntax.low is not None and syntax.high is not None and syntax.low > syntax.high:
                self.reporter.error(
                    syntax.span,
                    f"empty range {syntax.low}..{syntax.high}: the low end is above the high end",
                    Code.TYPES,
                )
            return m.BasicType(kind, syntax.low, syntax.high)
        if isinstance(syntax, s.ArrayTypeSyntax):
            return m.ArrayType(self.data_type(syntax.element))
        named = self.type_syntax.get(syntax.name.text)
        if named is None:
            word = FOREIGN_TYPES.get(syntax.name.text.lower())
            if word is not None and syntax.name.text not in self.type_syntax:
                self.reporter.error(
                    syntax.name.span, f"unknown data type '{syntax.name.text}'", Code.UNKNOWN_NAME, f"RoboSC writes '{word}'"
                )
                return m.ERROR
            self.reporter.unknown(syntax.name.span, "data type", syntax.name.text, self.type_syntax)
            return m.ERROR
        built = self._named_type(named)
        self.reporter.refer(syntax.name.span, built)
        return built

    def _named_type(self, syntax: NamedTypeSyntax) -> m.ObjectType | m.EnumType | m.ErrorType:
        key = id(syntax)
        if key in self._built:
            return self._built[key]
        if key in self._building:
            self.reporter.error(syntax.name.span, f"data type '{syntax.name.text}' contains itself", Code.TYPES)
            return m.ERROR
        self._building.add(key)
        built: m.ObjectType | m.EnumType
        if isinstance(syntax, s.ObjectTypeSyntax):
            properties = tuple(m.Property(p.name.text, self.data_type(p.type), p.span) for p in syntax.properties)
            built = m.ObjectType(syntax.name.text, properties, syntax.span)
        else:
            values: dict[str, m.EnumValue] = {}
            for rule in syntax.rules:
                values.setdefault(rule.value.text, m.EnumValue(rule.value.text, rule.value.span))
            built = m.EnumType(syntax.name.text, self.data_type(syntax.source), tuple(values.values()), (), syntax.span)
        self._building.discard(key)
        self._built[key] = built
        return built

    def build_all(self, expressions: ExpressionResolver) -> None:
        """Build every type and interface of the file, then the enum rules."""
        for definition in self.file.definitions:
            if isinstance(definition, s.InterfaceSyntax):
                self.interfaces.append(self.interface(definition))
            elif isinstance(definition, (s.ObjectTypeSyntax, s.EnumTypeSyntax)):
                built = self._named_type(definition)
                if not isinstance(built, m.ErrorType):
                    self.data_types.append(built)
        for data_type in self.data_types:
            if isinstance(data_type, m.EnumType):
                for value in data_type.values:
                    self.enum_values.setdefault(value.name, (data_type, value))
        for definition in self.file.definitions:
            if isinstance(definition, s.EnumTypeSyntax):
                enum = self._built.get(id(definition))
                if isinstance(enum, m.EnumType):
                    object.__setattr__(enum, "rules", self._enum_rules(enum, definition, expressions))

    def _enum_rules(
        self, enum: m.EnumType, syntax: s.EnumTypeSyntax, expressions: ExpressionResolver
    ) -> tuple[m.EnumRule, ...]:
        from robosc.language.resolver.expressions import ExprContext

        context = ExprContext(component=None, value_type=enum.source, where="an enum rule")
        rules = []
        for rule in syntax.rules:
            value = enum.value(rule.value.text)
            assert value is not None
            condition = None
            if rule.condition is not None:
                condition = expressions.condition(rule.condition, context, "an enum rule")
            rules.append(m.EnumRule(condition, value, rule.span))
        return tuple(rules)

    def add_imported(self, data_type: m.DataType) -> None:
        """Make a data type that an imported component uses known in this file."""
        if isinstance(data_type, m.ArrayType):
            self.add_imported(data_type.element)
            return
        if not isinstance(data_type, (m.ObjectType, m.EnumType)) or data_type in self.data_types:
            return
        self.data_types.append(data_type)
        if isinstance(data_type, m.EnumType):
            for value in data_type.values:
                self.enum_values.setdefault(value.name, (data_type, value))
            self.add_imported(data_type.source)
        else:
            for prop in data_type.properties:
                self.add_imported(prop.type)
