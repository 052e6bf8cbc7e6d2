"""The shape of the source tree (docs/architecture.md): the stages import downwards only, no
modules import each other in a circle, the runtime copied onto robots uses the standard library
alone, and no module or runtime class grows past the sizes a reader can hold."""

from __future__ import annotations

import ast
import sys
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parent.parent / "src"
PACKAGE = SRC / "robosc"

# Lowest first: a module may import from its own floor and those below it, never above.
FLOORS = (
    ("record", "wrapping", "jsonlines", "children"),
    ("language",),
    ("plant",),
    ("synthesis",),
    ("runtime",),
    ("codegen",),
    ("debug",),
    ("sim",),
    ("api",),
    ("editor",),
    ("cli", "__main__", "__init__"),
)
GENERATED = {"robosc.language.grammar_tables"}  # the grammar's parse tables, written by a program
MODULE_LINES = 800
ONBOARD_CLASS_LINES = 400


def module_names() -> dict[str, Path]:
    found = {}
    for path in PACKAGE.rglob("*.py"):
        parts = path.relative_to(SRC).with_suffix("").parts
        name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        found[name] = path
    return found


def imports(name: str, path: Path, modules: dict[str, Path]) -> set[str]:
    """The robosc modules ``name`` imports, wherever in it (functions and TYPE_CHECKING too)."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        targets: list[str] = []
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                origin = ".".join(base + ([node.module] if node.module else []))
            else:
                origin = node.module or ""
            submodules = [f"{origin}.{alias.name}" for alias in node.names if f"{origin}.{alias.name}" in modules]
            targets = submodules if len(submodules) == len(node.names) else [*submodules, origin]
        for target in targets:
            while target and target not in modules:
                target = target.rpartition(".")[0]
            if target.startswith("robosc") and target != name:
                found.add(target)
    return found


def graph() -> dict[str, set[str]]:
    modules = module_names()
    return {name: imports(name, path, modules) for name, path in modules.items()}


def floor(name: str) -> int:
    parts = name.split(".")
    top = parts[1] if len(parts) > 1 else "__init__"
    return next(i for i, names in enumerate(FLOORS) if top in names)


def circles(edges: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan's algorithm)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []

    def visit(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for other in sorted(edges.get(node, ())):
            if other not in index:
                visit(other)
                low[node] = min(low[node], low[other])
            elif other in on_stack:
                low[node] = min(low[node], index[other])
        if low[node] == index[node]:
            component = []
            while True:
                member = stack.pop()
                on_stack.discard(member)
                component.append(member)
                if member == node:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    limit = sys.getrecursionlimit()
    sys.setrecursionlimit(max(limit, 10_000))
    try:
        for node in sorted(edges):
            if node not in index:
                visit(node)
    finally:
        sys.setrecursionlimit(limit)
    return found


def test_every_top_level_module_has_a_floor() -> None:
    for name in module_names():
        floor(name)  # raises StopIteration for a folder or module FLOORS does not name


def test_no_module_imports_a_floor_above_its_own() -> None:
    upward = [
        f"{name} -> {other}"
        for name, others in sorted(graph().items())
        for other in sorted(others)
        if floor(other) > floor(name)
    ]
    assert upward == []


def test_no_modules_import_each_other_in_a_circle() -> None:
    assert circles(graph()) == []


def test_the_checks_see_a_circle_and_an_upward_import() -> None:
    edges = graph()
    edges["robosc.record"] = {*edges["robosc.record"], "robosc.cli.main"}  # record -> cli.main -> ... -> record
    assert any("robosc.record" in circle and "robosc.cli.main" in circle for circle in circles(edges))
    assert floor("robosc.cli.main") > floor("robosc.record")


def test_the_runtime_copied_onto_robots_uses_the_standard_library_only() -> None:
    onboard = PACKAGE / "runtime" / "onboard"
    for path in sorted(onboard.glob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom) and node.level == 0 and node.module is not None:
                names = [node.module]
            elif isinstance(node, ast.Import):
                names = [alias.name for alias in node.names]
            else:
                continue
            for imported in names:
                top = imported.split(".")[0]
                middleware = top in {"rospy", "rclpy", "actionlib", "rcl_interfaces", "rosgraph", "genpy"}
                messages = top.endswith("_msgs") or top.endswith("_srvs")
                assert top in sys.stdlib_module_names or middleware or messages, f"{path.name} imports {imported}"
                assert not imported.startswith("robosc"), f"{path.name} imports {imported}: use a relative import"


@pytest.mark.parametrize("name", sorted(set(module_names()) - GENERATED))
def test_no_module_is_longer_than_a_reader_can_hold(name: str) -> None:
    lines = len(module_names()[name].read_text(encoding="utf-8").splitlines())
    assert lines <= MODULE_LINES, f"{name}: {lines} lines"


def test_no_class_of_the_onboard_runtime_is_longer_than_a_reader_can_hold() -> None:
    for path in sorted((PACKAGE / "runtime" / "onboard").glob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ClassDef):
                length = (node.end_lineno or node.lineno) - node.lineno + 1
                assert length <= ONBOARD_CLASS_LINES, f"{path.name}: class {node.name} has {length} lines"
