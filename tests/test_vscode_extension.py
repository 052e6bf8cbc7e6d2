"""The VS Code extension (editors/vscode): compiled with tsc, its unit tests and grammar tests
(vscode-tmgrammar-test, snapshots of the example models) pass, it packages as a .vsix with
vsce, and the command line it starts the language server with is one robosc answers on.
No VS Code binary runs here: the editor's side of the protocol is covered by test_lsp.py."""

from __future__ import annotations

import asyncio
import json
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from ros_support import unavailable

ROOT = Path(__file__).resolve().parent.parent
EXTENSION = ROOT / "editors" / "vscode"


@pytest.fixture(scope="module")
def npm() -> str:
    found = shutil.which("npm")
    if found is None or not (EXTENSION / "node_modules" / ".bin" / "tsc").exists():
        unavailable("the extension's npm packages (npm ci in editors/vscode)")
    assert found is not None
    return found


def run_npm(npm: str, *args: str) -> subprocess.CompletedProcess[str]:
    done = subprocess.run([npm, *args], cwd=EXTENSION, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    return done


@pytest.fixture(scope="module")
def built(npm: str) -> str:
    run_npm(npm, "run", "compile")
    return npm


def test_unit_and_grammar_tests_pass(built: str) -> None:
    out = run_npm(built, "test").stdout
    assert "# fail 0" in out and "# pass 9" in out, out
    assert "basics.rscd run successful" in out, out  # the assertion test ran
    examples = sorted(p.name for p in (ROOT / "examples").glob("*.rscd"))
    for name in examples:  # every example model was tokenized and matched its snapshot
        assert f"tests/snap/{name} run successfully" in out, name


def test_grammar_test_fails_on_a_wrong_scope(built: str, tmp_path: Path) -> None:
    """The grammar test can fail: a copy of the grammar that scopes 'initial' and 'marked'
    differently does not pass it."""
    grammar = json.loads((EXTENSION / "syntaxes" / "robosc.tmLanguage.json").read_text())
    text = json.dumps(grammar).replace("storage.modifier.robosc", "storage.robosc")
    broken = tmp_path / "broken.tmLanguage.json"
    broken.write_text(text)
    shutil.copy(EXTENSION / "tests" / "grammar" / "basics.rscd", tmp_path)
    tool = EXTENSION / "node_modules" / ".bin" / "vscode-tmgrammar-test"
    args = [str(tool), "-g", broken.name, "basics.rscd"]
    # away from package.json, whose grammar the tool would otherwise take
    done = subprocess.run(args, cwd=tmp_path, capture_output=True, text=True)
    assert done.returncode != 0
    assert "missing required scopes: storage.modifier.robosc" in done.stdout + done.stderr
    (tmp_path / broken.name).write_text(json.dumps(grammar))  # the real grammar passes there
    assert subprocess.run(args, cwd=tmp_path, capture_output=True).returncode == 0


def test_packages_as_a_bundled_vsix_of_robosc_s_version(built: str, tmp_path: Path) -> None:
    """esbuild bundles the extension and its language client into one file (before: 211 files,
    node_modules and all, and vsce's warning); the extension's version is robosc's."""
    import robosc

    vsix = EXTENSION / "robosc.vsix"
    vsix.unlink(missing_ok=True)
    done = run_npm(built, "run", "package")
    assert "you should bundle your extension" not in done.stdout + done.stderr, done.stdout  # vsce's warning
    with zipfile.ZipFile(vsix) as archive:
        names = set(archive.namelist())
        manifest = json.loads(archive.read("extension/package.json"))
    for needed in (
        "extension/dist/extension.js",
        "extension/syntaxes/robosc.tmLanguage.json",
        "extension/language-configuration.json",
    ):
        assert needed in names, needed
    assert len(names) <= 12, sorted(names)
    assert not any(n.startswith(("extension/src/", "extension/tests/", "extension/node_modules/")) for n in names)
    assert manifest["contributes"]["languages"][0]["extensions"] == [".rscd"]
    assert manifest["main"] == "./dist/extension.js"
    assert manifest["version"] == robosc.__version__
    # the bundle loads (with a stand-in for the editor's 'vscode' module) and has the client in it
    stub = tmp_path / "node_modules" / "vscode"
    stub.mkdir(parents=True)
    (stub / "index.js").write_text("module.exports = new Proxy({}, { get: () => function () {} });\n")
    script = "const e = require(process.argv[1]); console.log(typeof e.activate, typeof e.deactivate);"
    loaded = subprocess.run(
        ["node", "-e", script, str(EXTENSION / "dist" / "extension.js")],
        env={**__import__("os").environ, "NODE_PATH": str(tmp_path / "node_modules")},
        capture_output=True, text=True, timeout=60,
    )
    assert loaded.stdout.split() == ["function", "function"], loaded.stderr
    assert "LanguageClient" in (EXTENSION / "dist" / "extension.js").read_text()


def test_the_server_command_line_starts_robosc_lsp(built: str, tmp_path: Path) -> None:
    """The extension's serverCommand (compiled JavaScript, run by node) names a command that
    answers LSP's initialize, search paths included."""
    program = Path(sys.executable).parent / "robosc"
    settings = {"program": str(program), "searchPaths": ["libs"], "ros": "none", "buildDirectory": "build", "liveViewPort": 8765}
    script = (
        "const c = require('./out/commands');"
        f"console.log(JSON.stringify(c.serverCommand({json.dumps(settings)}, {json.dumps(str(tmp_path))})));"
    )
    line = json.loads(subprocess.run(["node", "-e", script], cwd=EXTENSION, capture_output=True, text=True, check=True).stdout)
    assert line["args"] == ["lsp", "-I", str(tmp_path / "libs")]
    asyncio.run(_initialize(line["command"], line["args"]))


async def _initialize(command: str, args: list[str]) -> None:
    from lsprotocol import types as lsp
    from pytest_lsp import client_capabilities, make_test_lsp_client

    client = make_test_lsp_client()
    await client.start_io(command, *args)
    try:
        result = await asyncio.wait_for(
            client.initialize_session(lsp.InitializeParams(capabilities=client_capabilities("visual-studio-code"))), 60
        )
        assert result.server_info is not None and result.server_info.name == "robosc"
        capabilities = result.capabilities
        assert capabilities.hover_provider and capabilities.definition_provider and capabilities.rename_provider
    finally:
        await client.shutdown_session()
