"""Language-server benchmark (issue 12): over the real protocol (stdio, a pytest-lsp client),
the time from a didChange to the publishDiagnostics it causes, for the bundled examples and a
generated 5,000-line model (targets: 100 ms and 500 ms; typing in its middle and at its top,
a key at a time); and the time of a hover that shows an
added guard once synthesis has finished (target: 50 ms). Medians and maxima of N changes.

Run: python benchmarks/lsp.py [--repeat 20] [--lines 5000]
"""

from __future__ import annotations

import argparse
import asyncio
import statistics
import sys
import tempfile
import time
from pathlib import Path

from lsprotocol import types as lsp
from pytest_lsp import client_capabilities, make_test_lsp_client

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "benchmarks"))


async def change_to_diagnostics(client, uri: str, texts: list[str]) -> list[float]:
    times = []
    for version, text in enumerate(texts, 2):
        client.diagnostics.pop(uri, None)
        started = time.perf_counter()
        client.text_document_did_change(
            lsp.DidChangeTextDocumentParams(
                text_document=lsp.VersionedTextDocumentIdentifier(uri=uri, version=version),
                content_changes=[lsp.TextDocumentContentChangeWholeDocument(text=text)],
            )
        )
        while uri not in client.diagnostics:
            await asyncio.sleep(0.001)
        times.append(time.perf_counter() - started)
    return times


def open_doc(client, uri: str, text: str) -> None:
    client.text_document_did_open(
        lsp.DidOpenTextDocumentParams(text_document=lsp.TextDocumentItem(uri=uri, language_id="robosc", version=1, text=text))
    )


def line(label: str, times: list[float], target: float) -> None:
    median, worst = statistics.median(times) * 1000, max(times) * 1000
    verdict = "ok" if median <= target * 1000 else "OVER"
    print(f"{label:<44} median {median:7.1f} ms  max {worst:7.1f} ms  (target {target * 1000:.0f} ms: {verdict})")


async def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=20)
    parser.add_argument("--lines", type=int, default=5000)
    args = parser.parse_args()
    from language import generated_model

    client = make_test_lsp_client()
    await client.start_io(sys.executable, "-m", "robosc", "lsp")
    await client.initialize_session(lsp.InitializeParams(capabilities=client_capabilities("visual-studio-code")))
    with tempfile.TemporaryDirectory() as folder:
        for example in sorted((ROOT / "examples").glob("*.rscd")):
            target = Path(folder) / example.name
            text = example.read_text()
            target.write_text(text)
        for example in sorted((ROOT / "examples").glob("*.rscd")):
            text = example.read_text()
            if text.lstrip().startswith(("library", "//")) and "robot " not in text:
                continue
            uri = (Path(folder) / example.name).as_uri()
            open_doc(client, uri, text)
            texts = [text + "\n" + "// edit\n" * (i % 3) for i in range(args.repeat)]
            line(f"{example.name}: change -> diagnostics", await change_to_diagnostics(client, uri, texts), 0.1)
        big = generated_model(args.lines)
        uri = (Path(folder) / "big.rscd").as_uri()
        open_doc(client, uri, big)
        lines = big.count("\n")
        # typing a comment, a key at a time, into a line in the middle of the model, then at its top
        # (where every definition after the edit moves)
        for where, fraction in (("middle", 0.5), ("top", 0.02)):
            at = big.index("\n", int(len(big) * fraction))
            typed = " // typed here"
            texts = [big[:at] + typed[: i + 1] + big[at:] for i in range(min(len(typed), max(5, args.repeat // 2)))]
            line(f"{lines:,}-line model, typing at its {where}", await change_to_diagnostics(client, uri, texts), 0.5)
        # hover of an added guard, once synthesis is done
        shelf = ROOT / "examples" / "shelf_picker.rscd"
        uri = (Path(folder) / "shelf_picker.rscd").as_uri()
        open_doc(client, uri, shelf.read_text())
        lines = shelf.read_text().splitlines()
        at = next(i for i, t in enumerate(lines) if t.strip().startswith("requirement pick needs"))
        params = lsp.HoverParams(
            text_document=lsp.TextDocumentIdentifier(uri=uri),
            position=lsp.Position(line=at, character=lines[at].index("pick needs") + 1),
        )
        while "added" not in str((await client.text_document_hover_async(params)).contents):
            await asyncio.sleep(0.05)
        times = []
        for _ in range(args.repeat):
            started = time.perf_counter()
            await client.text_document_hover_async(params)
            times.append(time.perf_counter() - started)
        line("hover of an added guard (shelf_picker)", times, 0.05)
    await client.shutdown_session()


if __name__ == "__main__":
    asyncio.run(main())
