"""``robosc lsp`` end to end: a real LSP client (pytest-lsp) talks to the server over stdio."""

from __future__ import annotations

import asyncio
import sys
from pathlib import Path

import pytest

pytest.importorskip("pygls", reason="robosc lsp needs pygls (pip install '.[lsp]')")

import pytest_lsp
from lsprotocol import types as lsp
from pytest_lsp import ClientServerConfig, LanguageClient, client_capabilities

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"


@pytest_lsp.fixture(config=ClientServerConfig(server_command=[sys.executable, "-m", "robosc", "lsp"]))
async def client(lsp_client: LanguageClient):
    await lsp_client.initialize_session(
        lsp.InitializeParams(capabilities=client_capabilities("visual-studio-code"), root_uri=EXAMPLES.as_uri())
    )
    yield
    await lsp_client.shutdown_session()


def open_document(client: LanguageClient, path: Path, text: str | None = None, version: int = 1) -> str:
    uri = path.as_uri()
    client.diagnostics.clear()
    client.text_document_did_open(
        lsp.DidOpenTextDocumentParams(
            text_document=lsp.TextDocumentItem(
                uri=uri, language_id="robosc", version=version, text=path.read_text() if text is None else text
            )
        )
    )
    return uri


def change(client: LanguageClient, uri: str, text: str, version: int) -> None:
    client.diagnostics.clear()
    client.text_document_did_change(
        lsp.DidChangeTextDocumentParams(
            text_document=lsp.VersionedTextDocumentIdentifier(uri=uri, version=version),
            content_changes=[lsp.TextDocumentContentChangeWholeDocument(text=text)],
        )
    )


async def diagnostics_of(client: LanguageClient, uri: str, timeout: float = 20.0) -> list[lsp.Diagnostic]:
    """The diagnostics published for ``uri`` since the last open or change (a test fails, not
    hangs, without them)."""
    end = asyncio.get_running_loop().time() + timeout
    while uri not in client.diagnostics:
        if asyncio.get_running_loop().time() > end:
            raise AssertionError(f"no diagnostics for {uri} in {timeout:g} s")
        await asyncio.sleep(0.01)
    return list(client.diagnostics.pop(uri))


@pytest.mark.asyncio
async def test_diagnostics_on_open_and_on_change(client: LanguageClient, tmp_path: Path) -> None:
    text = (EXAMPLES / "maze_solver.rscd").read_text()
    path = tmp_path / "maze_solver.rscd"
    uri = open_document(client, path, text)
    assert await diagnostics_of(client, uri) == []  # the example is clean
    broken = text.replace("Distance.front = wall_front", "Distance.fron = wall_front")
    change(client, uri, broken, 2)
    found = await diagnostics_of(client, uri)
    assert len(found) == 1
    d = found[0]
    line = broken.splitlines().index(next(x for x in broken.splitlines() if "Distance.fron =" in x))
    column = broken.splitlines()[line].index("fron")
    assert d.severity == lsp.DiagnosticSeverity.Error and d.source == "robosc"
    assert d.code == "rule-14"  # the code robosc check gives
    assert (d.range.start.line, d.range.start.character) == (line, column)
    assert (d.range.end.line, d.range.end.character) == (line, column + len("fron"))
    assert d.message == "unknown state or variable 'fron' in component 'Distance'\nhint: did you mean 'front'?"
    # the quick fix the hint names
    actions = await client.text_document_code_action_async(
        lsp.CodeActionParams(
            text_document=lsp.TextDocumentIdentifier(uri=uri),
            range=d.range,
            context=lsp.CodeActionContext(diagnostics=[d]),
        )
    )
    assert actions is not None and len(actions) == 1
    action = actions[0]
    assert isinstance(action, lsp.CodeAction) and action.title == "Change to 'front'"
    assert action.edit is not None and action.edit.changes is not None
    assert list(action.edit.changes[uri]) == [lsp.TextEdit(range=d.range, new_text="front")]
    change(client, uri, text, 3)  # fixed again
    assert await diagnostics_of(client, uri) == []


async def quick_fixes(client: LanguageClient, uri: str, found: list[lsp.Diagnostic]) -> list[lsp.CodeAction]:
    actions = await client.text_document_code_action_async(
        lsp.CodeActionParams(
            text_document=lsp.TextDocumentIdentifier(uri=uri),
            range=found[0].range,
            context=lsp.CodeActionContext(diagnostics=found),
        )
    )
    assert actions is not None
    return [a for a in actions if isinstance(a, lsp.CodeAction)]


@pytest.mark.asyncio
async def test_quick_fixes_escape_a_keyword_and_add_a_range(client: LanguageClient, tmp_path: Path) -> None:
    text = (
        "robot R {\n"
        "    component C {\n"
        "        outgoing message beep with type: none incoming message act with type: none\n"
        "        behaviour {\n"
        "            variable n: integer = 12\n"
        "            initial marked state state { on response from beep do n := n + 1 goto ^state }\n"
        "        }\n"
        "    }\n"
        "    requirement act needs C.n < 3\n"
        "}\n"
    )
    path = tmp_path / "r.rscd"
    uri = open_document(client, path, text)
    found = await diagnostics_of(client, uri)
    assert [d.code for d in found] == ["syntax"]
    (action,) = await quick_fixes(client, uri, found)
    assert action.title == "Escape the keyword: '^state'"
    text = apply_edit(text, action.edit, uri)
    assert "initial marked state ^state {" in text
    change(client, uri, text, 2)
    found = await diagnostics_of(client, uri)
    assert [d.code for d in found] == ["rule-9"]  # n takes part in synthesis: it needs a range
    (action,) = await quick_fixes(client, uri, found)
    assert action.title == "Add the range (0..12)"  # 0..10, widened to hold the initial 12
    text = apply_edit(text, action.edit, uri)
    assert "variable n: integer(0..12) = 12" in text
    change(client, uri, text, 3)
    assert await diagnostics_of(client, uri) == []


@pytest.mark.asyncio
async def test_errors_inside_a_library_go_to_the_library(client: LanguageClient, tmp_path: Path) -> None:
    library = (EXAMPLES / "emergency_stop.rscd").read_text()
    (tmp_path / "emergency_stop.rscd").write_text(library.replace("goto stopped", "goto stoped", 1))
    model = tmp_path / "line_follower.rscd"
    uri = open_document(client, model, (EXAMPLES / "line_follower.rscd").read_text())
    in_library = await diagnostics_of(client, (tmp_path / "emergency_stop.rscd").as_uri())
    assert in_library and all(d.severity == lsp.DiagnosticSeverity.Error for d in in_library)
    assert "'stoped'" in in_library[0].message and in_library[0].range.start.line == 9
    await diagnostics_of(client, uri)  # the model's own, published too


@pytest.mark.asyncio
async def test_outline_of_a_model(client: LanguageClient) -> None:
    uri = open_document(client, EXAMPLES / "maze_solver.rscd")
    symbols = await client.text_document_document_symbol_async(
        lsp.DocumentSymbolParams(text_document=lsp.TextDocumentIdentifier(uri=uri))
    )
    assert symbols is not None
    names = [(s.name, s.detail) for s in symbols]
    assert ("Distance", "component") in names and ("Platform", "component") in names
    assert ("WallFront", "datatype") in names and ("laser_scan", "interface") in names
    assert "requirement movement needs" in [s.name for s in symbols]
    platform = next(s for s in symbols if s.name == "Platform")
    children = [(c.name, c.detail) for c in platform.children or []]
    assert ("movement", "message") in children and ("ready", "state") in children and ("turning", "state") in children
    line = (EXAMPLES / "maze_solver.rscd").read_text().splitlines().index("    component Platform {")
    assert platform.selection_range.start == lsp.Position(line=line, character=14)


@pytest.mark.asyncio
async def test_hover_shows_what_synthesis_added_and_why(client: LanguageClient) -> None:
    path = EXAMPLES / "shelf_picker.rscd"
    uri = open_document(client, path)
    assert await diagnostics_of(client, uri) == []
    lines = path.read_text().splitlines()
    line = next(i for i, text in enumerate(lines) if text.strip().startswith("requirement pick needs"))
    at = lsp.Position(line=line, character=lines[line].index("pick needs") + 1)
    end = asyncio.get_running_loop().time() + 20
    while True:  # synthesis runs in the background; until then the hover says so
        hover = await client.text_document_hover_async(
            lsp.HoverParams(text_document=lsp.TextDocumentIdentifier(uri=uri), position=at)
        )
        assert hover is not None
        text = hover.contents.value  # type: ignore[union-attr]
        if "running" not in text or asyncio.get_running_loop().time() > end:
            break
        await asyncio.sleep(0.1)
    assert "**action `pick`** of `Arm`" in text
    assert "- `pick.c_trigger` needs `Base.at_shelf`; **synthesis added** `Tray.empty or Tray.one`" in text
    assert "so: the system would block" in text  # the explanation, as robosc synthesize gives it
    assert "- `pick.c_reset` needs `true`" in text  # no condition added there
    state = next(i for i, text in enumerate(lines) if "Tray.two" in text)
    hover = await client.text_document_hover_async(
        lsp.HoverParams(
            text_document=lsp.TextDocumentIdentifier(uri=uri),
            position=lsp.Position(line=state, character=lines[state].index("Tray.two") + 6),
        )
    )
    assert hover is not None and "**state `Tray.two`**" in hover.contents.value  # type: ignore[union-attr]
    # where it is used: two gotos and a requirement (not the comment on line 3)
    used = sorted(i + 1 for i, t in enumerate(lines) if "goto two" in t or "Tray.two" in t)
    assert used == [84, 94, 102]
    assert hover.contents.value.endswith(f"used 3 times: line {', '.join(map(str, sorted(used)))}")  # type: ignore[union-attr]


def where(path: Path, text: str, nth: int = 0, offset: int = 0) -> lsp.Position:
    """The position of the ``nth`` occurrence of ``text`` in the file (plus ``offset`` characters)."""
    lines = path.read_text().splitlines()
    found = [(i, line.index(text)) for i, line in enumerate(lines) if text in line]
    line, column = found[nth]
    return lsp.Position(line=line, character=column + offset)


@pytest.mark.asyncio
async def test_definition_and_references(client: LanguageClient) -> None:
    path = EXAMPLES / "maze_solver.rscd"
    uri = open_document(client, path)
    await diagnostics_of(client, uri)
    doc = lsp.TextDocumentIdentifier(uri=uri)
    # Platform.ready in a requirement -> the state 'ready' of Platform
    use = where(path, "Platform.ready", 0, len("Platform.") + 1)
    found = await client.text_document_definition_async(lsp.DefinitionParams(text_document=doc, position=use))
    assert isinstance(found, lsp.Location) and found.uri == uri
    assert found.range.start == where(path, "initial marked state ready", 0, len("initial marked state "))
    # 'goto turning' -> the state turning
    found = await client.text_document_definition_async(
        lsp.DefinitionParams(text_document=doc, position=where(path, "goto turning", 0, len("goto t")))
    )
    assert isinstance(found, lsp.Location) and found.range.start == where(path, "state turning", 0, len("state "))
    # the data type of a message -> its declaration
    found = await client.text_document_definition_async(
        lsp.DefinitionParams(text_document=doc, position=where(path, "type: WallFront", 0, len("type: W")))
    )
    assert isinstance(found, lsp.Location) and found.range == lsp.Range(
        start=where(path, "enum WallFront from", 0, len("enum ")), end=where(path, "enum WallFront from", 0, len("enum WallFront"))
    )
    # every use of Platform.ready: three requirements, 'goto ready' and its declaration
    uses = await client.text_document_references_async(
        lsp.ReferenceParams(
            text_document=doc, position=use, context=lsp.ReferenceContext(include_declaration=True)
        )
    )
    assert uses is not None
    starts = sorted((u.range.start.line, u.range.start.character) for u in uses)
    expected = sorted(
        [(where(path, "initial marked state ready").line, where(path, "initial marked state ready").character + 21)]
        + [(p.line, p.character + len("Platform.")) for p in (where(path, "Platform.ready", n) for n in range(3))]
        + [(where(path, "goto ready").line, where(path, "goto ready").character + len("goto "))]
    )
    assert starts == expected
    # from the declaration too, without it
    uses = await client.text_document_references_async(
        lsp.ReferenceParams(
            text_document=doc,
            position=where(path, "initial marked state ready", 0, len("initial marked state r")),
            context=lsp.ReferenceContext(include_declaration=False),
        )
    )
    assert uses is not None and len(uses) == 4


@pytest.mark.asyncio
async def test_definition_in_a_library(client: LanguageClient) -> None:
    path = EXAMPLES / "line_follower.rscd"
    uri = open_document(client, path)
    await diagnostics_of(client, uri)
    use = where(path, "EmergencyStop.stopped", 0, len("EmergencyStop.") + 1)
    found = await client.text_document_definition_async(
        lsp.DefinitionParams(text_document=lsp.TextDocumentIdentifier(uri=uri), position=use)
    )
    library = EXAMPLES / "emergency_stop.rscd"
    assert isinstance(found, lsp.Location) and found.uri == library.as_uri()
    assert "stopped" in library.read_text().splitlines()[found.range.start.line]


@pytest.mark.asyncio
async def test_completion_in_context(client: LanguageClient, tmp_path: Path) -> None:
    text = (EXAMPLES / "maze_solver.rscd").read_text()
    path = tmp_path / "maze_solver.rscd"
    uri = open_document(client, path, text)
    assert await diagnostics_of(client, uri) == []

    async def labels(typed_after: str, anchor: str) -> list[str]:
        """Type ``typed_after`` right after ``anchor`` (the model no longer checks) and complete there."""
        at = text.index(anchor) + len(anchor)
        edited = text[:at] + typed_after + text[at:]
        change(client, uri, edited, 2)
        await diagnostics_of(client, uri)
        before = edited[: at + len(typed_after)]
        line = before.count("\n")
        character = len(before.rsplit("\n", 1)[-1])
        found = await client.text_document_completion_async(
            lsp.CompletionParams(
                text_document=lsp.TextDocumentIdentifier(uri=uri), position=lsp.Position(line=line, character=character)
            )
        )
        assert isinstance(found, lsp.CompletionList)
        return [item.label for item in found.items]

    # the states of the component being written, after goto
    assert await labels("\n                on request to turn_left goto ", "state turning {") == ["ready", "turning"]
    # its own communications after 'on response from'
    got = await labels("\n                on response from ", "state turning {")
    assert got == ["movement", "turn_left", "turn_right", "rotate_done"]
    # a component's states and variables after 'Distance.'
    got = await labels(" and Distance.", "requirement turn_left needs Platform.ready")
    assert got == ["sensing", "front", "right", "diag_right"]
    # enum values after '='
    got = await labels(" and Distance.front = ", "requirement turn_left needs Platform.ready")
    assert {"wall_front", "no_wall_front", "wall_right"} <= set(got) and "ready" not in got
    # elsewhere: keywords and names in scope
    got = await labels("\n    ", "provide movement with { linear: { x: 0.3 } }")
    assert {"requirement", "component", "Distance", "Platform", "movement", "WallFront"} <= set(got)


@pytest.mark.asyncio
async def test_folding_ranges(client: LanguageClient) -> None:
    uri = open_document(client, EXAMPLES / "maze_solver.rscd")
    ranges = await client.text_document_folding_range_async(
        lsp.FoldingRangeParams(text_document=lsp.TextDocumentIdentifier(uri=uri))
    )
    lines = (EXAMPLES / "maze_solver.rscd").read_text().splitlines()
    platform = lines.index("    component Platform {")
    ready = next(i for i, line in enumerate(lines) if "initial marked state ready {" in line)
    spans = {(r.start_line, r.end_line) for r in ranges or []}
    assert (ready, ready + 3) in spans  # the state ready { ... } over its four lines
    assert any(start == platform and end > ready for start, end in spans)
    assert all(end > start for start, end in spans)


@pytest.mark.asyncio
async def test_formatting_is_robosc_fmt(client: LanguageClient, tmp_path: Path) -> None:
    messy = "robot   R {\ncomponent S {\n   outgoing message sense with type: boolean\n}\n}\n"
    uri = open_document(client, tmp_path / "r.rscd", messy)
    edits = await client.text_document_formatting_async(
        lsp.DocumentFormattingParams(
            text_document=lsp.TextDocumentIdentifier(uri=uri), options=lsp.FormattingOptions(tab_size=4, insert_spaces=True)
        )
    )
    from robosc.api import format_text

    assert edits is not None and len(edits) == 1
    assert edits[0].new_text == format_text(messy) and edits[0].range.start == lsp.Position(line=0, character=0)


@pytest.mark.asyncio
async def test_the_server_survives_any_text(client: LanguageClient, tmp_path: Path) -> None:
    text = (EXAMPLES / "pick_and_light.rscd").read_text()
    (tmp_path / "emergency_stop.rscd").write_text((EXAMPLES / "emergency_stop.rscd").read_text())
    uri = open_document(client, tmp_path / "p.rscd", text)
    await diagnostics_of(client, uri)
    import random

    rng = random.Random(7)
    version = 1
    for _ in range(30):  # cut, duplicate and garble parts of the model
        a, b = sorted(rng.randrange(len(text)) for _ in range(2))
        mutated = rng.choice([text[:a] + text[b:], text[:b] + text[a:], text[:a] + "\x00{^(" + text[a:], text[:a]])
        version += 1
        change(client, uri, mutated, version)
        await diagnostics_of(client, uri)
        symbols = await client.text_document_document_symbol_async(
            lsp.DocumentSymbolParams(text_document=lsp.TextDocumentIdentifier(uri=uri))
        )
        assert symbols is None or isinstance(symbols, list)
    change(client, uri, text, version + 1)
    assert await diagnostics_of(client, uri) == []


def test_positions_count_utf16_units() -> None:
    from robosc.editor.positions import to_offset, to_range
    from robosc.language.source import Span

    lines = ['x := "é😀" + nope']
    column = lines[0].index("nope") + 1  # characters, from 1
    r = to_range(Span("f", 1, column, 1, column + 4, 0, 0), lines)
    assert (r.start.line, r.start.character, r.end.character) == (0, column - 1 + 1, column - 1 + 1 + 4)  # 😀 is two units
    assert to_offset(lines[0], lsp.Position(line=0, character=r.start.character)) == column - 1


def apply_edit(text: str, edit: lsp.WorkspaceEdit | None, uri: str) -> str:
    """``text`` after the edits a workspace edit makes in ``uri`` (ASCII text)."""
    assert edit is not None and edit.changes is not None and set(edit.changes) == {uri}, edit
    lines = text.splitlines(keepends=True)

    def offset(p: lsp.Position) -> int:
        return sum(len(line) for line in lines[: p.line]) + p.character

    for e in sorted(edit.changes[uri], key=lambda e: offset(e.range.start), reverse=True):
        text = text[: offset(e.range.start)] + e.new_text + text[offset(e.range.end) :]
    return text


async def rename(client: LanguageClient, uri: str, at: lsp.Position, new_name: str) -> lsp.WorkspaceEdit | None:
    return await client.text_document_rename_async(
        lsp.RenameParams(text_document=lsp.TextDocumentIdentifier(uri=uri), position=at, new_name=new_name)
    )


async def prepare_rename(client: LanguageClient, uri: str, at: lsp.Position) -> lsp.PrepareRenameResult | None:
    return await client.text_document_prepare_rename_async(
        lsp.PrepareRenameParams(text_document=lsp.TextDocumentIdentifier(uri=uri), position=at)
    )


@pytest.mark.asyncio
async def test_rename_a_state_everywhere_and_escape_a_keyword(client: LanguageClient) -> None:
    from robosc.api import check_text

    path = EXAMPLES / "maze_solver.rscd"
    text = path.read_text()
    uri = open_document(client, path)
    await diagnostics_of(client, uri)
    use = where(path, "Platform.ready", 1, len("Platform.r"))
    prepared = await prepare_rename(client, uri, use)
    assert isinstance(prepared, lsp.PrepareRenamePlaceholder) and prepared.placeholder == "ready"
    assert prepared.range.start == where(path, "Platform.ready", 1, len("Platform."))
    edit = await rename(client, uri, use, "waiting")
    assert edit is not None and edit.changes is not None and len(edit.changes[uri]) == 5  # declaration, 3 uses, goto
    after = apply_edit(text, edit, uri)
    assert after.count("Platform.waiting") == 3 and "initial marked state waiting {" in after and "goto waiting" in after
    assert "ready" not in after.replace("already", "")
    assert check_text(after, str(path)).ok
    # a keyword as the new name is written with its ^, from the declaration too
    declared = where(path, "initial marked state ready", 0, len("initial marked state re"))
    after = apply_edit(text, await rename(client, uri, declared, "state"), uri)
    assert after.count("Platform.^state") == 3 and "initial marked state ^state {" in after and "goto ^state" in after
    assert check_text(after, str(path)).ok


@pytest.mark.asyncio
async def test_rename_a_component_and_refusals(client: LanguageClient) -> None:
    from pygls.exceptions import JsonRpcException

    from robosc.api import check_text

    path = EXAMPLES / "maze_solver.rscd"
    text = path.read_text()
    uri = open_document(client, path)
    await diagnostics_of(client, uri)
    after = apply_edit(text, await rename(client, uri, where(path, "component Platform", 0, len("component P")), "Base"), uri)
    assert "component Base {" in after and after.count("Base.ready") == 3 and "Platform" not in after
    assert check_text(after, str(path)).ok
    # a name that is taken: the other state of Platform
    with pytest.raises(JsonRpcException, match="not renamed: the model would not check"):
        await rename(client, uri, where(path, "state turning", 0, len("state t")), "ready")
    with pytest.raises(JsonRpcException, match="'2fast' is not a name"):
        await rename(client, uri, where(path, "state turning", 0, len("state t")), "2fast")
    # a keyword is not a name to rename
    keyword = where(path, "requirement turn_left", 0, 2)
    prepared = await prepare_rename(client, uri, keyword)
    assert prepared is None
    with pytest.raises(JsonRpcException, match="no name to rename here"):
        await rename(client, uri, keyword, "x")


@pytest.mark.asyncio
async def test_renamed_communication_keeps_its_ros_name(client: LanguageClient, tmp_path: Path) -> None:
    """A communication without an identifier is on ROS under its name; renamed, it keeps it."""
    from robosc.api import check_text

    text = (
        "robot R {\n"
        "    component C {\n"
        "        incoming message beep with type: none\n"
        "        behaviour { initial marked state s { on request to beep goto s } }\n"
        "    }\n"
        "    requirement beep needs C.s\n"
        "}\n"
    )
    path = tmp_path / "r.rscd"
    path.write_text(text)
    uri = open_document(client, path, text)
    assert await diagnostics_of(client, uri) == []
    after = apply_edit(text, await rename(client, uri, where(path, "beep with", 0, 1), "chirp"), uri)
    assert 'incoming message chirp with identifier: "beep", type: none' in after
    assert "to chirp goto" in after and "requirement chirp needs" in after
    result = check_text(after, str(path))
    assert result.ok and result.model is not None
    assert result.model.components[0].communications[0].ros_name == "beep"


FLEET = (
    "robot Cell {\n"
    "    component bot[3] {\n"
    "        incoming message take with type: none\n"
    "        behaviour {\n"
    "            initial marked state free { on request to take goto busy }\n"
    "            marked state busy { on request to take goto free }\n"
    "        }\n"
    "    }\n"
    "    for r in bot {\n"
    "        requirement r.take needs count(q in bot: q.busy) <= 1\n"
    "    }\n"
    "    requirement bot2.take needs bot1.free\n"
    "}\n"
)


@pytest.mark.asyncio
async def test_a_fleet_in_the_editor(client: LanguageClient, tmp_path: Path) -> None:
    """Completion, hover and rename know instances: bot2.take is the component's `take`."""
    from pygls.exceptions import JsonRpcException

    from robosc.api import check_text

    path = tmp_path / "cell.rscd"
    path.write_text(FLEET)
    uri = open_document(client, path, FLEET)
    assert await diagnostics_of(client, uri) == []

    async def complete(text: str, at: lsp.Position) -> list[str]:
        change(client, uri, text, 2)
        await diagnostics_of(client, uri)
        found = await client.text_document_completion_async(
            lsp.CompletionParams(text_document=lsp.TextDocumentIdentifier(uri=uri), position=at)
        )
        assert isinstance(found, lsp.CompletionList)
        return [item.label for item in found.items]

    # after an instance variable: the instance's communications, states
    typed = FLEET.replace("needs bot1.free\n", "needs bot1.free and r.\n")
    line = typed.splitlines().index("    requirement bot2.take needs bot1.free and r.")
    got = await complete(typed.replace("    requirement bot2", "    for r in bot {} requirement bot2"), lsp.Position(line=line, character=len("    for r in bot {} requirement bot2.take needs bot1.free and r.")))
    assert got == ["take", "free", "busy"]
    # after `in`: the groups
    typed = FLEET.replace("for r in bot {", "for r in  {")
    assert await complete(typed, lsp.Position(line=8, character=len("    for r in "))) == ["bot"]

    change(client, uri, FLEET, 3)
    await diagnostics_of(client, uri)
    hovered = await client.text_document_hover_async(
        lsp.HoverParams(text_document=lsp.TextDocumentIdentifier(uri=uri), position=where(path, "message take", 0, 9))
    )
    assert hovered is not None
    text = hovered.contents.value  # type: ignore[union-attr]
    assert "**incoming message `take`** of each of `bot1` .. `bot3`: `none`, ROS name `bot1/take`" in text
    assert "used 4 times: line 5, 6, 10, 12" in text  # once per place, not once per instance
    assert text.count("**incoming message") == 1
    # renaming the declaration renames it in every instance's use, and keeps the ROS name
    after = apply_edit(FLEET, await rename(client, uri, where(path, "message take", 0, 9), "grab"), uri)
    assert "r.grab needs" in after and "requirement bot2.grab needs" in after and "to grab goto" in after
    assert 'incoming message grab with identifier: "take", type: none' in after
    result = check_text(after, str(path))
    assert result.model is not None and result.model.communication("bot2.grab").ros_name == "bot2/take"
    # a state used through an instance (bot1.free) renames the component's state
    after = apply_edit(FLEET, await rename(client, uri, where(path, "bot1.free", 0, 6), "idle"), uri)
    assert "initial marked state idle {" in after and "bot1.idle" in after and check_text(after, str(path)).ok
    # an instance is named by its group: not renamed alone
    with pytest.raises(JsonRpcException, match="instance 1 of 'bot'"):
        await rename(client, uri, where(path, "bot1.free", 0, 1), "first")
