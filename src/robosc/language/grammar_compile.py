"""Compiles ``grammar.lark`` into ``grammar_tables.py``: what Lark computes from the grammar
(its LALR(1) parse table, its lexer's terminals in matching order, how it shapes trees),
written as Python literals that :mod:`robosc.language.lalr` runs without Lark.

Run after changing the grammar (a test fails while the tables are out of date)::

    python -m robosc.language.grammar_compile

Lark is needed here only, at development time: parsing a model does not import it.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

GRAMMAR = Path(__file__).with_name("grammar.lark")
TABLES = Path(__file__).with_name("grammar_tables.py")
# the tables, by the start symbols they parse from: a whole file, and (for the language
# server's reparsing) one definition of a robot or a library alone
STARTS = {"FILE": ["start"], "PIECES": ["robot_def", "library_def"]}
# Words that are keywords only where a name cannot stand: lexed as NAME, and read as the
# keyword by the parser where it has no action on a name (robosc.language.lalr.parse), so
# that models of the original tool naming something so still load. Lark's basic lexer would
# reserve them; the tests run Lark with the same rule.
SOFT_KEYWORDS = ("FOR", "IN", "NAMESPACE")


def compile_tables(grammar: str, starts: list[str]) -> dict[str, Any]:
    """The tables of Lark's LALR parser with its basic lexer, as plain data."""
    from lark import Lark
    from lark.lexer import UnlessCallback
    from lark.parsers.lalr_analysis import Shift

    parser = Lark(grammar, parser="lalr", lexer="basic", propagate_positions=True, maybe_placeholders=False, start=starts)
    lexer = parser.parser.lexer
    scanner = lexer.scanner  # built on first use: the terminals left after keywords are folded into NAME
    keywords: dict[str, dict[str, str]] = {}
    for name, callback in lexer.callback.items():
        assert isinstance(callback, UnlessCallback), f"unexpected lexer callback on {name}"
        folded = callback.scanner.terminals
        assert all(not t.pattern.flags for t in folded), "keywords with regex flags are not supported"
        keywords[name] = {t.pattern.value: t.name for t in folded if t.name not in SOFT_KEYWORDS}
    soft = {t.pattern.value: t.name for t in parser.terminals if t.name in SOFT_KEYWORDS}
    table = parser.parser.parser.parser.parse_table
    rules = list(parser.rules)
    index = {id(rule): number for number, rule in enumerate(rules)}
    # Lark numbers its states in an order that varies from run to run (string hashing):
    # number them in the order a walk from the start states meets them, symbols in sorted
    # order, so that the same grammar always gives the same tables
    number: dict[int, int] = {}
    for start in sorted(table.start_states):
        number.setdefault(table.start_states[start], len(number))
    for start in sorted(table.end_states):
        number.setdefault(table.end_states[start], len(number))
    walk = list(number)
    for state in walk:
        for symbol in sorted(table.states[state], key=str):
            action, argument = table.states[state][symbol]
            if action is Shift and argument not in number:
                number[argument] = len(number)
                walk.append(argument)
    assert len(number) == len(table.states), "states that no start reaches"
    states: list[dict[str, int]] = []
    for state in walk:
        actions: dict[str, int] = {}
        for symbol in sorted(table.states[state], key=str):
            action, argument = table.states[state][symbol]
            # a shift (or a goto) as the state it goes to, a reduction as ~ the rule's number
            actions[str(symbol)] = number[argument] if action is Shift else ~index[id(argument)]
        states.append(actions)
    shaped = []
    for rule in rules:
        keep_all = rule.options.keep_all_tokens
        include = [
            (i, not symbol.is_term and symbol.name.startswith("_"))  # a _rule's children are inlined
            for i, symbol in enumerate(rule.expansion)
            if keep_all or not (symbol.is_term and symbol.filter_out)
        ]
        filtered = len(include) < len(rule.expansion) or any(inline for _, inline in include)
        shaped.append(
            (
                str(rule.origin.name),
                len(rule.expansion),
                str(rule.alias or rule.origin.name),
                bool(rule.options.expand1 and not rule.alias),  # a ?rule with one child is that child
                tuple(~i if inline else i for i, inline in include) if filtered else None,
            )
        )
    return {
        "terminals": tuple((t.name, t.pattern.to_regexp()) for t in scanner.terminals),
        "keywords": keywords,
        "soft": soft,
        "ignore": tuple(sorted(lexer.ignore_types)),
        "newline": tuple(sorted(lexer.newline_types)),
        "literals": {t.name: t.pattern.value for t in sorted(parser.terminals, key=lambda t: t.name) if t.pattern.type == "str"},
        "rules": tuple(shaped),
        "states": tuple(states),
        "start": {str(k): number[v] for k, v in sorted(table.start_states.items())},
        "end": {str(k): number[v] for k, v in sorted(table.end_states.items())},
    }


def _write_tables(name: str, tables: dict[str, Any]) -> list[str]:
    lines = [f"{name}: dict[str, Any] = {{"]
    for key, value in tables.items():
        if key in ("rules", "states"):
            lines.append(f"    {key!r}: (")
            lines += [f"        {item!r}," for item in value]
            lines.append("    ),")
        else:
            lines.append(f"    {key!r}: {value!r},")
    lines.append("}")
    return lines


def render(grammar: str) -> str:
    """The text of ``grammar_tables.py`` for this grammar."""
    import lark

    lines = [
        f"# Generated from grammar.lark by `python -m robosc.language.grammar_compile` (lark {lark.__version__}).",
        "# Do not edit: change the grammar and run the command again (a test checks these are current).",
        '"""The parse tables of grammar.lark, run by :mod:`robosc.language.lalr`."""',
        "",
        "from typing import Any",
    ]
    for name, starts in STARTS.items():
        lines += ["", *_write_tables(name, compile_tables(grammar, starts))]
    return "\n".join(lines) + "\n"


def main() -> None:
    import lark

    if not lark.__version__.startswith("1."):
        # ROS 2's rosidl-parser wheel pulls in lark-parser 0.12, which writes over lark 1.x
        raise SystemExit(
            f"robosc's grammar needs lark 1.x to compile, found {lark.__version__}: "
            "pip install --force-reinstall --no-deps 'lark>=1.1.9'"
        )
    text = render(GRAMMAR.read_text(encoding="utf-8"))
    TABLES.write_text(text, encoding="utf-8")
    print(f"wrote {TABLES} ({len(text.splitlines())} lines)", file=sys.stderr)


if __name__ == "__main__":
    main()
