"""Turns the parse tree into :mod:`robosc.language.syntax` nodes.

The grammar (``grammar.lark``) says what is valid; this module only builds
nodes from it. One method per grammar rule or alias.
"""

from __future__ import annotations

import re
from typing import Any

from robosc.language import syntax as s
from robosc.language.codes import Code
from robosc.language.keywords import KEYWORDS
from robosc.language.lalr import Meta, Token, Tree
from robosc.language.source import Span

MAX_INT = 2**63 - 1
MAX_STRING = 65536
MAX_NAME = 100  # names become package, node and file names (diagrams: plant_<component>_<comm>.svg)
MAX_EXPRESSION_DEPTH = 100  # the depth of an expression tree: later stages recurse over it, and
# generated Python code nests it in parentheses (CPython reads at most 200 levels); a run of one
# associative operator is a balanced tree (Transformer._run), so it counts a few levels
ASSOCIATIVE = ("and", "or")


class SyntaxProblem(Exception):
    """A problem found while building nodes (the grammar alone cannot see it)."""

    def __init__(self, span: Span, message: str, hint: str | None = None, code: Code = Code.SYNTAX) -> None:
        super().__init__(message)
        self.span = span
        self.message = message
        self.code = code
        self.hint = hint


_ESCAPES = {"n": "\n", "t": "\t", "r": "\r", "b": "\b", "f": "\f", "0": "\0"}
_ESCAPE = re.compile(r"\\(.)", re.DOTALL)
_CONTROL = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\x7f-\x9f]")


def _unescape_string(raw: str) -> str:
    """The value of a string literal: quotes removed, backslash escapes applied."""
    return _ESCAPE.sub(lambda m: _ESCAPES.get(m.group(1), m.group(1)), raw[1:-1])


class SyntaxBuilder:
    """One method per rule or alias, called with the node's position and its built children.
    ``lines`` and ``offset`` place a text parsed alone (one definition) in its file."""

    def __init__(self, path: str, comments: tuple[s.Comment, ...], lines: int = 0, offset: int = 0) -> None:
        self.path = path
        self.comments = comments
        self.lines, self.offset = lines, offset
        self._depth: dict[int, int] = {}
        self._chain: dict[int, int] = {}
        # a run of one associative operator (`a or b or c ...`) as it grows: the perfect trees
        # of its operands so far, biggest (first operands) first, each with its operand count
        self._forests: dict[int, list[tuple[s.Expr, int]]] = {}
        self._replaced: list[s.Expr] = []  # nodes of a run built over again: kept, so that no new
        # node takes the id of one and its depth (the dicts above are keyed by id)

    def build(self, tree: Tree) -> s.FileSyntax:
        """Build bottom-up without recursion (no depth limit from Python's stack)."""
        built: dict[int, Any] = {}
        methods: dict[str, Any] = {}
        for subtree in tree.iter_subtrees():
            children = [built.pop(id(c)) if isinstance(c, Tree) else c for c in subtree.children]
            rule = str(subtree.data)
            method = methods.get(rule)
            if method is None:
                method = methods[rule] = getattr(self, rule)
            built[id(subtree)] = method(subtree.meta, children)
        result: s.FileSyntax = built[id(tree)]
        return result

    # -- helpers -------------------------------------------------------------
    def _span(self, meta: Meta) -> Span:
        if meta.empty:
            return s.NO_SPAN
        lines, offset = self.lines, self.offset
        return Span(
            self.path,
            meta.line + lines,
            meta.column,
            meta.end_line + lines,
            meta.end_column,
            meta.start_pos + offset,
            meta.end_pos + offset,
        )

    def token_span(self, token: Token) -> Span:
        lines, offset = self.lines, self.offset
        return Span(
            self.path,
            token.line + lines,
            token.column,
            token.end_line + lines,
            token.end_column,
            token.start_pos + offset,
            token.end_pos + offset,
        )

    def _expr(self, node: s.Expr, *children: Any) -> s.Expr:
        """Bound the depth of expression trees, which later stages walk recursively. A long
        run of one operator (``a and b and c ...``) is a deep tree too, and is named so."""
        depth = 1 + max((self._depth.get(id(c), 0) for c in children), default=0)
        chain = 1
        if isinstance(node, s.Binary) and isinstance(node.left, s.Binary) and node.left.op == node.op:
            chain = self._chain.get(id(node.left), 1) + 1
        if depth > MAX_EXPRESSION_DEPTH:
            if isinstance(node, s.Binary) and chain + 1 > MAX_EXPRESSION_DEPTH // 2:
                message = (
                    f"expression more than {MAX_EXPRESSION_DEPTH} levels deep "
                    f"({chain + 1} operands joined by '{node.op}' in a row)"
                )
                hint = "split the condition, e.g. over several requirements on the same event"
                raise SyntaxProblem(node.span, message, hint, code=Code.LIMIT)
            raise SyntaxProblem(
                node.span, f"expression nested more than {MAX_EXPRESSION_DEPTH} levels deep", code=Code.LIMIT
            )
        self._depth[id(node)] = depth
        if chain > 1:
            self._chain[id(node)] = chain
        return node

    # -- file ----------------------------------------------------------------
    def start(self, meta: Meta, ch: list[Any]) -> s.FileSyntax:
        file: s.FileSyntax = ch[0]
        return file

    def robot(self, meta: Meta, ch: list[Any]) -> s.FileSyntax:
        return s.FileSyntax("robot", ch[0], tuple(ch[1:]), self.comments, self._span(meta))

    def library(self, meta: Meta, ch: list[Any]) -> s.FileSyntax:
        return s.FileSyntax("library", ch[0], tuple(ch[1:]), self.comments, self._span(meta))

    def name(self, meta: Meta, ch: list[Token]) -> s.Name:
        text = str(ch[0])
        if text in KEYWORDS:
            raise SyntaxProblem(
                self._span(meta), f"'{text}' is a keyword, not a name", f"write '^{text}' to use it as a name"
            )
        name = text[1:] if text.startswith("^") else text
        if len(name) > MAX_NAME:
            raise SyntaxProblem(
                self._span(meta),
                f"name of {len(name)} characters is too long (at most {MAX_NAME}: names become file, "
                "package and ROS names)",
                code=Code.LIMIT,
            )
        return s.Name(name, self._span(meta))

    # -- components ------------------------------------------------------------
    @staticmethod
    def _instances(ch: list[Any]) -> s.Instances | None:
        """The ``[count]`` and the options among a component's children (taken out of ``ch``)."""
        count = next((c for c in ch if isinstance(c, s.IntLit)), None)
        options = next((c for c in ch if isinstance(c, s.Instances)), None)
        ch[:] = [c for c in ch if not isinstance(c, (s.IntLit, s.Instances))]
        if count is None and options is None:
            return None
        if options is None:
            return s.Instances(count, span=count.span if count else s.NO_SPAN)
        return s.Instances(count, options.namespace, options.initial, options.span)

    def local_component(self, meta: Meta, ch: list[Any]) -> s.LocalComponentSyntax:
        instances = self._instances(ch)
        return s.LocalComponentSyntax(ch[0], tuple(ch[1:]), self._span(meta), instances)

    def imported_component(self, meta: Meta, ch: list[Any]) -> s.ImportedComponentSyntax:
        instances = self._instances(ch)
        return s.ImportedComponentSyntax(ch[0], ch[1], ch[2], self._span(meta), instances)

    def instances(self, meta: Meta, ch: list[Token]) -> s.IntLit:
        return s.IntLit(self._int(ch[0]), self._span(meta))

    def options(self, meta: Meta, ch: list[Any]) -> s.Instances:
        namespace = next((c for c in ch if isinstance(c, s.StrLit)), None)
        initial = next((c for c in ch if isinstance(c, tuple)), ())
        return s.Instances(None, namespace, initial, self._span(meta))

    def namespace(self, meta: Meta, ch: list[Any]) -> s.StrLit:
        token = ch[1]
        literal = self.string_literal(meta, [token])
        return s.StrLit(literal.raw, literal.value, self.token_span(token))

    def initial_states(self, meta: Meta, ch: list[Any]) -> tuple[s.Name, ...]:
        return tuple(c for c in ch if isinstance(c, s.Name))

    def behaviour(self, meta: Meta, ch: list[Any]) -> s.BehaviourSyntax:
        return s.BehaviourSyntax(tuple(ch), self._span(meta))

    def direction(self, meta: Meta, ch: list[Token]) -> str:
        return str(ch[0])

    def identifier(self, meta: Meta, ch: list[Token]) -> s.StrLit:
        return self.string_literal(meta, ch)

    def links(self, meta: Meta, ch: list[s.Name]) -> s.Name:
        return ch[0]

    @staticmethod
    def _optional(ch: list[Any], kind: type) -> tuple[Any | None, list[Any]]:
        """Split off an optional leading child of ``kind``."""
        if ch and isinstance(ch[0], kind):
            return ch[0], ch[1:]
        return None, ch

    def message(self, meta: Meta, ch: list[Any]) -> s.MessageSyntax:
        direction, name, *rest = ch
        identifier, rest = self._optional(rest, s.StrLit)
        links = rest[1] if len(rest) > 1 else None
        return s.MessageSyntax(direction, name, identifier, rest[0], links, self._span(meta))

    def service(self, meta: Meta, ch: list[Any]) -> s.ServiceSyntax:
        name, *rest = ch
        identifier, rest = self._optional(rest, s.StrLit)
        links = rest[2] if len(rest) > 2 else None
        return s.ServiceSyntax(name, identifier, rest[0], rest[1], links, self._span(meta))

    def action(self, meta: Meta, ch: list[Any]) -> s.ActionSyntax:
        name, *rest = ch
        identifier, rest = self._optional(rest, s.StrLit)
        links = rest[3] if len(rest) > 3 else None
        return s.ActionSyntax(name, identifier, rest[0], rest[1], rest[2], links, self._span(meta))

    def variable(self, meta: Meta, ch: list[Any]) -> s.VariableSyntax:
        return s.VariableSyntax(ch[0], ch[1], ch[2] if len(ch) > 2 else None, self._span(meta))

    def state(self, meta: Meta, ch: list[Any]) -> s.StateSyntax:
        flags = {str(c) for c in ch if isinstance(c, Token)}
        rest = [c for c in ch if not isinstance(c, Token)]
        return s.StateSyntax(rest[0], "initial" in flags, "marked" in flags, tuple(rest[1:]), self._span(meta))

    def result_type(self, meta: Meta, ch: list[Token]) -> str:
        return str(ch[0])

    preposition = result_type

    def result_transition(self, meta: Meta, ch: list[Any]) -> s.ResultTransitionSyntax:
        result, preposition, communication, *rest = ch
        assignments: tuple[s.AssignmentSyntax, ...] = ()
        target = None
        for part in rest:
            if isinstance(part, tuple):
                assignments = part
            else:
                target = part
        return s.ResultTransitionSyntax(result, preposition, communication, assignments, target, self._span(meta))

    def do(self, meta: Meta, ch: list[s.AssignmentSyntax]) -> tuple[s.AssignmentSyntax, ...]:
        return tuple(ch)

    def goto(self, meta: Meta, ch: list[s.Name]) -> s.Name:
        return ch[0]

    def guard(self, meta: Meta, ch: list[Any]) -> tuple[str, s.Expr]:
        return ("guard", ch[0])

    def tau_transition(self, meta: Meta, ch: list[Any]) -> s.TauTransitionSyntax:
        guard = None
        target = None
        for part in ch:
            if isinstance(part, tuple):
                guard = part[1]
            else:
                target = part
        return s.TauTransitionSyntax(guard, target, self._span(meta))

    def assignment(self, meta: Meta, ch: list[Any]) -> s.AssignmentSyntax:
        return s.AssignmentSyntax(ch[0], ch[1], self._span(meta))

    # -- data types ------------------------------------------------------------
    def basic_type(self, meta: Meta, ch: list[Token]) -> s.BasicTypeSyntax:
        return s.BasicTypeSyntax(str(ch[0]), span=self._span(meta))

    def integer_type(self, meta: Meta, ch: list[int]) -> s.BasicTypeSyntax:
        if ch:
            return s.BasicTypeSyntax("integer", ch[0], ch[1], self._span(meta))
        return s.BasicTypeSyntax("integer", span=self._span(meta))

    def _int(self, token: Token) -> int:
        """An integer literal, refused when it does not fit in 64 bits (as CIF's and ROS's do)."""
        text = str(token)
        if len(text.lstrip("0")) > 19 or int(text) > MAX_INT:
            shown = text if len(text) <= 30 else f"{text[:12]}...{text[-6:]} ({len(text)} digits)"
            raise SyntaxProblem(
                self.token_span(token),
                f"integer {shown} is too large: integers are 64-bit, at most {MAX_INT}",
                code=Code.LIMIT,
            )
        return int(text)

    def signed_int(self, meta: Meta, ch: list[Token]) -> int:
        return -self._int(ch[1]) if len(ch) == 2 else self._int(ch[0])

    def array_type(self, meta: Meta, ch: list[Any]) -> s.ArrayTypeSyntax:
        return s.ArrayTypeSyntax(ch[0], self._span(meta))

    def named_type(self, meta: Meta, ch: list[s.Name]) -> s.NamedTypeSyntax:
        return s.NamedTypeSyntax(ch[0], self._span(meta))

    def datatype_def(self, meta: Meta, ch: list[Any]) -> Any:
        return ch[0]

    def object_type(self, meta: Meta, ch: list[Any]) -> s.ObjectTypeSyntax:
        return s.ObjectTypeSyntax(ch[0], tuple(ch[1:]), self._span(meta))

    def property(self, meta: Meta, ch: list[Any]) -> s.PropertySyntax:
        return s.PropertySyntax(ch[0], ch[1], self._span(meta))

    def enum_type(self, meta: Meta, ch: list[Any]) -> s.EnumTypeSyntax:
        return s.EnumTypeSyntax(ch[0], ch[1], tuple(ch[2:]), self._span(meta))

    def enum_rule(self, meta: Meta, ch: list[Any]) -> s.EnumRuleSyntax:
        return s.EnumRuleSyntax(ch[0], ch[1], self._span(meta))

    def enum_default(self, meta: Meta, ch: list[Any]) -> s.EnumRuleSyntax:
        return s.EnumRuleSyntax(None, ch[0], self._span(meta))

    def interface(self, meta: Meta, ch: list[s.Name]) -> s.InterfaceSyntax:
        return s.InterfaceSyntax(ch[0], ch[1], ch[2], self._span(meta))

    # -- requirements and provide ----------------------------------------------
    def needs_requirement(self, meta: Meta, ch: list[Any]) -> s.RequirementSyntax:
        return s.RequirementSyntax("needs", ch[0], ch[1], self._span(meta))

    def disables_requirement(self, meta: Meta, ch: list[Any]) -> s.RequirementSyntax:
        return s.RequirementSyntax("disables", ch[1], ch[0], self._span(meta))

    def single_event(self, meta: Meta, ch: list[s.Name]) -> s.EventsSyntax:
        return s.EventsSyntax((ch[0],), False, self._span(meta))

    def event_set(self, meta: Meta, ch: list[s.Name]) -> s.EventsSyntax:
        return s.EventsSyntax(tuple(ch), True, self._span(meta))

    def qualified_name(self, meta: Meta, ch: list[s.Name]) -> s.QualifiedName:
        return s.QualifiedName(ch[0], ch[1], self._span(meta))

    def for_each(self, meta: Meta, ch: list[Any]) -> s.ForEachSyntax:
        return s.ForEachSyntax(ch[1], ch[3], tuple(ch[4:]), self._span(meta))

    def provide(self, meta: Meta, ch: list[Any]) -> s.ProvideSyntax:
        return s.ProvideSyntax(ch[0], ch[1], ch[2] if len(ch) > 2 else None, self._span(meta))

    def object_value(self, meta: Meta, ch: list[s.FieldValueSyntax]) -> s.ObjectValueSyntax:
        return s.ObjectValueSyntax(tuple(ch), self._span(meta))

    def field_value(self, meta: Meta, ch: list[Any]) -> s.FieldValueSyntax:
        return s.FieldValueSyntax(ch[0], ch[1], self._span(meta))

    # -- expressions -------------------------------------------------------------
    def binary(self, meta: Meta, ch: list[Any]) -> s.Expr:
        left, op, right = ch
        if str(op) in ASSOCIATIVE:
            return self._run(str(op), left, right, self._span(meta))
        return self._expr(s.Binary(str(op), left, right, self._span(meta)), left, right)

    def _run(self, op: str, left: s.Expr, right: s.Expr, span: Span) -> s.Expr:
        """``left op right`` where ``op`` is associative (``and``, ``or``: the same whichever
        way the operands group): a run of it (``a or b or c ...``, as users write a condition
        on every robot of a fleet) is kept a balanced tree, a few levels deep however long, not
        one level per operand (later stages recurse over it). Its operands stay in order, and
        each node's span covers its own; the formatter writes it back as written."""
        forest = self._forests.pop(id(left), None) if isinstance(left, s.Binary) and left.op == op else None
        if forest is not None:
            self._replaced.append(left)
        forest = list(forest) if forest is not None else [(left, 1)]
        forest.append((right, 1))
        while len(forest) > 1 and forest[-1][1] == forest[-2][1]:  # two alike: one twice the size
            (a, size), (b, _) = forest[-2], forest.pop()
            forest[-1] = (self._joined(op, a, b), 2 * size)
        node = forest[0][0]
        for tree, _ in forest[1:]:
            node = self._joined(op, node, tree)
            self._replaced.append(node)
        if not isinstance(node, s.Binary):  # (cannot happen: two operands at least)
            return node
        node = self._expr(s.Binary(op, node.left, node.right, span), node.left, node.right)
        self._forests[id(node)] = forest
        return node

    def _joined(self, op: str, left: s.Expr, right: s.Expr) -> s.Expr:
        a, b = left.span, right.span
        span = Span(a.path, a.line, a.column, b.end_line, b.end_column, a.start, b.end)
        return self._expr(s.Binary(op, left, right, span), left, right)

    def unary(self, meta: Meta, ch: list[Any]) -> s.Expr:
        op, operand = ch
        return self._expr(s.Unary(str(op), operand, self._span(meta)), operand)

    def paren(self, meta: Meta, ch: list[Any]) -> s.Expr:
        return self._expr(s.Paren(ch[0], self._span(meta)), ch[0])

    def quantifier(self, meta: Meta, ch: list[Any]) -> s.Expr:
        kind, binder, _, group, body = ch
        name = s.Name(str(kind), self.token_span(kind))
        return self._expr(s.Quantifier(name, binder, group, body, self._span(meta)), body)

    def call(self, meta: Meta, ch: list[Any]) -> s.Expr:
        kind, *args = ch
        name = s.Name(str(kind), self.token_span(kind))
        return self._expr(s.Call(name, tuple(args), self._span(meta)), *args)

    def int_literal(self, meta: Meta, ch: list[Token]) -> s.IntLit:
        return s.IntLit(self._int(ch[0]), self._span(meta))

    def double_literal(self, meta: Meta, ch: list[Token]) -> s.DoubleLit:
        return s.DoubleLit(str(ch[0]), self._span(meta))

    def negative_int(self, meta: Meta, ch: list[Token]) -> s.Expr:
        return s.Unary("-", self.int_literal(meta, [ch[1]]), self._span(meta))

    def negative_double(self, meta: Meta, ch: list[Token]) -> s.Expr:
        return s.Unary("-", self.double_literal(meta, [ch[1]]), self._span(meta))

    def string_literal(self, meta: Meta, ch: list[Token]) -> s.StrLit:
        raw = str(ch[0])
        if len(raw) > MAX_STRING + 2:
            raise SyntaxProblem(
                self._span(meta),
                f"string of {len(raw) - 2} characters is too long (at most {MAX_STRING})",
                code=Code.LIMIT,
            )
        value = _unescape_string(raw)
        control = _CONTROL.search(value)
        if control is not None:
            raise SyntaxProblem(
                self._control_span(meta, raw),
                f"the string holds the control character U+{ord(control.group()):04X}: a NUL ends a ROS "
                "string, and the others garble diagrams, logs and terminals",
                "only tab (\\t), newline (\\n) and carriage return (\\r) are allowed in strings",
                code=Code.TEXT,
            )
        return s.StrLit(raw, value, self._span(meta))

    def _control_span(self, meta: Meta, raw: str) -> Span:
        """The span of the first control character of the literal ``raw`` as written: the
        character itself or its backslash escape."""
        at = 1
        while at < len(raw) - 1:
            size = 2 if raw[at] == "\\" else 1
            char = _ESCAPES.get(raw[at + 1], raw[at + 1]) if size == 2 else raw[at]
            if _CONTROL.match(char):
                break
            at += size
        else:
            return self._span(meta)
        before = raw[:at]
        line = meta.line + self.lines + before.count("\n")
        column = at - before.rfind("\n") if "\n" in before else meta.column + at
        start = meta.start_pos + self.offset + at
        return Span(self.path, line, column, line, column + size, start, start + size)

    def bool_literal(self, meta: Meta, ch: list[Token]) -> s.BoolLit:
        return s.BoolLit(str(ch[0]) == "true", self._span(meta))

    def access(self, meta: Meta, ch: list[Any]) -> s.Access:
        head = None if isinstance(ch[0], Token) else ch[0]
        return s.Access(head, tuple(ch[1:]), self._span(meta))

    def index_step(self, meta: Meta, ch: list[Token]) -> s.IndexStep:
        return s.IndexStep(self._int(ch[0]), self._span(meta))

    def member_step(self, meta: Meta, ch: list[s.Name]) -> s.MemberStep:
        return s.MemberStep(ch[0], self._span(meta))
