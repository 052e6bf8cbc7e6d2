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
    assert found.range.start == where(path, "initial marked state ready")
    # 'goto turning' -> the state turning
    found = await client.text_document_definition_async(
        lsp.DefinitionParams(text_document=doc, position=where(path, "goto turning", 0, len("goto t")))
    )
    assert isinstance(found, lsp.Location) and found.range.start == where(path, "state turning")
    # the data type of a message -> its declaration
    found = await client.text_document_definition_async(
        lsp.DefinitionParams(text_document=doc, position=where(path, "type: WallFront", 0, len("type: W")))
    )
    assert isinstance(found, lsp.Location) and found.range.start == where(path, "enum WallFront from LaserScan")
    # every use of Platform.ready: three requirements, 'goto ready' and its declaration
    uses = await client.text_document_references_async(
        lsp.ReferenceParams(
            text_document=doc, position=use, context=lsp.ReferenceContext(include_declaration=True)
        )
    )
    assert uses is not None
    starts = sorted((u.range.start.line, u.range.start.character) for u in uses)
    expected = sorted(
        [(where(path, "initial marked state ready").line, where(path, "initial marked state ready").character)]
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
