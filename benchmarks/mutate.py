"""Mutated models and the whole pipeline over them: shared by the fuzz test
(``tests/test_fuzz.py``) and the large fuzz run (``benchmarks/fuzz.py``).

A mutation deletes, duplicates, swaps or replaces tokens of a bundled example, or inserts
random bytes. :func:`pipeline` runs a text through check, synthesize and generate (ROS 1
and ROS 2, and the supervisor module compiled); every outcome must be a model, diagnostics
or a documented refusal, never another exception.
"""

from __future__ import annotations

import random
import re
import tempfile
from pathlib import Path

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
TOKEN = re.compile(
    r"\s+|[A-Za-z_^][A-Za-z0-9_]*|\d+\.\d+|\d+|\"[^\"]*\"|'[^']*'|//[^\n]*|:=|->|=>|!=|>=|<=|\.\.|.", re.S
)
SOURCES = {p.name: p.read_text() for p in sorted(EXAMPLES.glob("*.rscd"))}
KINDS = ("delete", "duplicate", "swap", "replace", "bytes")


def mutate(text: str, rng: random.Random, count: int) -> str:
    """``text`` with ``count`` random token mutations."""
    tokens = TOKEN.findall(text)
    for _ in range(count):
        kind = rng.choice(KINDS)
        i, j = rng.randrange(len(tokens)), rng.randrange(len(tokens))
        if kind == "delete":
            del tokens[i]
        elif kind == "duplicate":
            tokens.insert(i, tokens[i])
        elif kind == "swap":
            tokens[i], tokens[j] = tokens[j], tokens[i]
        elif kind == "replace":
            tokens[i] = tokens[j]
        else:
            tokens.insert(i, bytes(rng.randrange(256) for _ in range(rng.randint(1, 6))).decode("latin-1"))
    return "".join(tokens)


def pipeline(text: str, name: str, workdir: Path) -> str:
    """Check, synthesize and generate ``text`` (as ``workdir/name``, next to the library the
    examples import). Returns what happened: "errors", "library", "no supervisor",
    "refused by ROS" or "generated". Any other exception is a crash and propagates."""
    from robosc.api import check_text, plan_supervisor, synthesize_model
    from robosc.codegen.module import render_module
    from robosc.codegen.ros import RosError, generate

    (workdir / "emergency_stop.rscd").write_text(SOURCES["emergency_stop.rscd"])
    result = check_text(text, str(workdir / name))
    if result.model is None:
        assert result.errors, "no model and no errors"
        result.render()
        return "errors"
    if result.model.kind != "robot":
        return "library"
    synthesized = synthesize_model(result.model)
    if not synthesized.ok:
        return "no supervisor"
    plan = plan_supervisor(synthesized)
    compile(render_module(plan), "<generated>", "exec")
    try:
        with tempfile.TemporaryDirectory(dir=workdir) as out:
            for ros in (1, 2):
                generate(plan, ros, "controller", Path(out) / f"ros{ros}")
    except RosError:
        return "refused by ROS"
    return "generated"
