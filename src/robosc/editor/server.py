"""``robosc lsp``: the language server (pygls, over stdio). Documents are checked on open
and, debounced, on change, by the same language stage as ``robosc check``; the outline comes
from the syntax tree; formatting is ``robosc fmt``. A request that fails answers with nothing
rather than ending the server."""

from __future__ import annotations

import asyncio
import functools
import logging
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from lsprotocol import types as lsp
from pygls.exceptions import JsonRpcException
from pygls.lsp.server import LanguageServer
from pygls.uris import from_fs_path, to_fs_path

from robosc.editor.background import Synthesizer
from robosc.editor.diagnostics import by_file, code_actions
from robosc.editor.navigation import Index, RenameError, declarations
from robosc.editor.outline import folds, outline
from robosc.editor.rename import error_codes
from robosc.language.parser import gc_paused
from robosc.language.reparse import Reparser
from robosc.runtime.onboard import VERSION as __version__

DEBOUNCE_SECONDS = 0.02  # a burst of keystrokes is checked once; short against the 100 ms target
log = logging.getLogger(__name__)


class RoboscServer(LanguageServer):
    def __init__(self, search_paths: Sequence[str] = ()) -> None:
        super().__init__("robosc", __version__)
        self.search_paths = [Path(p) for p in search_paths]
        self.pending: dict[str, asyncio.TimerHandle] = {}
        self.published: dict[str, set[str]] = {}  # document uri -> uris it published diagnostics for
        self.checked: dict[str, list[Any]] = {}  # uri -> [checked model, synthesis's hover notes or None]
        self.indexes: dict[str, Index] = {}  # uri -> the names resolved by its last check
        self.reparsers: dict[str, Reparser] = {}  # uri -> the parses of its definitions
        self.synthesizer = Synthesizer(self.synthesized)

    def path_of(self, uri: str) -> str:
        return to_fs_path(uri) or uri

    def check(self, uri: str) -> None:
        """Check the open document ``uri`` and publish what it found, in it and in its libraries."""
        from robosc.api import check_text

        self.pending.pop(uri, None)
        try:
            document = self.workspace.get_text_document(uri)
            reparser = self.reparsers.setdefault(uri, Reparser())
            with gc_paused():  # resolving and checking too
                result = check_text(document.source, self.path_of(uri), self.search_paths, reparser)
            found = by_file(result)
            self.indexes[uri] = Index(
                self.path_of(uri),
                result.references,
                result.sources,
                declarations(result.model),
                error_codes(result.diagnostics),
            )
        except Exception:  # never end the server on a model
            log.exception("checking %s failed", uri)
            return
        published = set()
        for path, diagnostics in found.items():
            target = uri if path == self.path_of(uri) else (from_fs_path(path) or path)
            published.add(target)
            self.text_document_publish_diagnostics(lsp.PublishDiagnosticsParams(uri=target, diagnostics=diagnostics))
        for stale in self.published.get(uri, set()) - published:
            self.text_document_publish_diagnostics(lsp.PublishDiagnosticsParams(uri=stale, diagnostics=[]))
        self.published[uri] = published
        if result.model is not None and result.model.kind == "robot":
            self.synthesize(uri, result.model, document.source)

    def synthesize(self, uri: str, model: Any, text: str) -> None:
        """Synthesis of the checked model in a process of its own, once typing pauses: typing
        goes on meanwhile; hover shows the result once it is there (and only for the text it
        was made from)."""
        entry: list[Any] = [model, None]
        self.checked[uri] = entry
        self.synthesizer.request(uri, entry, text, self.path_of(uri), [str(p) for p in self.search_paths])

    def synthesized(self, uri: str, token: Any, notes: dict[str, list[str]] | None) -> None:
        entry = self.checked.get(uri)
        if entry is not None and entry is token:
            entry[1] = notes

    def current_index(self, uri: str) -> Index | None:
        """The names of ``uri`` as it is now (checked at once if a check is pending)."""
        if uri in self.pending:
            self.pending.pop(uri).cancel()
            self.check(uri)
        return self.indexes.get(uri)

    def syntax(self, uri: str) -> tuple[Any, list[str]]:
        """The open document's syntax tree (None when it does not parse) and its lines."""
        from robosc.language.source import SourceFile

        document = self.workspace.get_text_document(uri)
        # the document's reparser: what its checks parsed already is not parsed again
        parsed = self.reparsers.setdefault(uri, Reparser()).parse(SourceFile(self.path_of(uri), document.source))
        return parsed.syntax, document.source.splitlines()

    def schedule(self, uri: str) -> None:
        """Check ``uri`` once typing pauses for DEBOUNCE_SECONDS."""
        old = self.pending.pop(uri, None)
        if old is not None:
            old.cancel()
        loop = asyncio.get_event_loop()
        self.pending[uri] = loop.call_later(DEBOUNCE_SECONDS, self.check, uri)


def failed(message: str) -> JsonRpcException:
    """A request that could not be done, with why (LSP's RequestFailed)."""
    return JsonRpcException(message, code=-32803)


def answer(what: str) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """A request handler that answers with nothing, logged, when it fails: a model never
    ends the server."""

    def wrap(handler: Callable[..., Any]) -> Callable[..., Any]:
        @functools.wraps(handler)
        def guarded(ls: RoboscServer, params: Any) -> Any:
            try:
                return handler(ls, params)
            except Exception:
                log.exception("%s failed", what)
                return None

        return guarded

    return wrap


def create(search_paths: Sequence[str] = ()) -> RoboscServer:
    server = RoboscServer(search_paths)

    @server.feature(lsp.INITIALIZE)
    def initialize(ls: RoboscServer, params: lsp.InitializeParams) -> None:
        options = params.initialization_options
        if isinstance(options, dict) and isinstance(options.get("searchPaths"), list):
            ls.search_paths += [Path(str(p)) for p in options["searchPaths"]]

    @server.feature(lsp.TEXT_DOCUMENT_DID_OPEN)
    def did_open(ls: RoboscServer, params: lsp.DidOpenTextDocumentParams) -> None:
        ls.check(params.text_document.uri)

    @server.feature(lsp.TEXT_DOCUMENT_DID_CHANGE)
    def did_change(ls: RoboscServer, params: lsp.DidChangeTextDocumentParams) -> None:
        ls.schedule(params.text_document.uri)

    @server.feature(lsp.TEXT_DOCUMENT_DID_CLOSE)
    def did_close(ls: RoboscServer, params: lsp.DidCloseTextDocumentParams) -> None:
        uri = params.text_document.uri
        handle = ls.pending.pop(uri, None)
        if handle is not None:
            handle.cancel()
        ls.checked.pop(uri, None)
        ls.indexes.pop(uri, None)
        ls.reparsers.pop(uri, None)
        ls.synthesizer.stop(uri)
        for target in ls.published.pop(uri, {uri}):
            ls.text_document_publish_diagnostics(lsp.PublishDiagnosticsParams(uri=target, diagnostics=[]))

    @server.feature(lsp.TEXT_DOCUMENT_DOCUMENT_SYMBOL)
    @answer("outline")
    def symbols(ls: RoboscServer, params: lsp.DocumentSymbolParams) -> list[lsp.DocumentSymbol] | None:
        tree, lines = ls.syntax(params.text_document.uri)
        return outline(tree, lines) if tree is not None else None

    @server.feature(lsp.TEXT_DOCUMENT_FOLDING_RANGE)
    @answer("folding")
    def folding(ls: RoboscServer, params: lsp.FoldingRangeParams) -> list[lsp.FoldingRange] | None:
        tree, _ = ls.syntax(params.text_document.uri)
        return folds(tree) if tree is not None else None

    @server.feature(lsp.TEXT_DOCUMENT_HOVER)
    @answer("hover")
    def hover(ls: RoboscServer, params: lsp.HoverParams) -> lsp.Hover | None:
        from robosc.editor.hover import describe, used_at, word_at

        entry = ls.checked.get(params.text_document.uri)
        if entry is None:
            return None
        document = ls.workspace.get_text_document(params.text_document.uri)
        lines = document.source.splitlines()
        line = lines[params.position.line] if params.position.line < len(lines) else ""
        name = word_at(line, params.position.character)
        text = describe(entry[0], entry[1], name) if name else None
        if text is None:
            return None
        index = ls.indexes.get(params.text_document.uri)
        if index is not None:
            text += used_at(index.uses(params.position, declaration=False), params.text_document.uri)
        return lsp.Hover(contents=lsp.MarkupContent(kind=lsp.MarkupKind.Markdown, value=text))

    @server.feature(lsp.TEXT_DOCUMENT_DEFINITION)
    @answer("definition")
    def definition(ls: RoboscServer, params: lsp.DefinitionParams) -> lsp.Location | None:
        index = ls.indexes.get(params.text_document.uri)
        return index.definition(params.position) if index is not None else None

    @server.feature(lsp.TEXT_DOCUMENT_REFERENCES)
    @answer("references")
    def references(ls: RoboscServer, params: lsp.ReferenceParams) -> list[lsp.Location] | None:
        index = ls.indexes.get(params.text_document.uri)
        return index.uses(params.position, params.context.include_declaration) if index is not None else None

    @server.feature(lsp.TEXT_DOCUMENT_PREPARE_RENAME)
    @answer("prepare rename")
    def prepare_rename(ls: RoboscServer, params: lsp.PrepareRenameParams) -> lsp.PrepareRenamePlaceholder | None:
        index = ls.current_index(params.text_document.uri)
        found = index.name_at(params.position) if index is not None else None
        if found is None:
            return None
        target, span = found
        return lsp.PrepareRenamePlaceholder(range=index.location(span).range, placeholder=target.name)  # type: ignore[union-attr]

    @server.feature(lsp.TEXT_DOCUMENT_RENAME)
    def rename(ls: RoboscServer, params: lsp.RenameParams) -> lsp.WorkspaceEdit | None:
        from robosc.editor.rename import renamed

        index = ls.current_index(params.text_document.uri)
        if index is None:
            raise failed("the model has not been checked yet")
        try:
            edits = index.rename(params.position, params.new_name)
            return renamed(index, edits, ls.search_paths)
        except RenameError as problem:
            raise failed(str(problem)) from None
        except Exception:
            log.exception("rename failed")
            raise failed("rename failed: see the server's log") from None

    @server.feature(lsp.TEXT_DOCUMENT_COMPLETION, lsp.CompletionOptions(trigger_characters=[".", " "]))
    @answer("completion")
    def completion(ls: RoboscServer, params: lsp.CompletionParams) -> lsp.CompletionList | None:
        from robosc.editor.completion import complete
        from robosc.editor.positions import to_offset

        document = ls.workspace.get_text_document(params.text_document.uri)
        before = document.source[: to_offset(document.source, params.position)]
        entry = ls.checked.get(params.text_document.uri)  # the last model that checked
        return lsp.CompletionList(is_incomplete=False, items=complete(before, entry[0] if entry else None))

    @server.feature(
        lsp.TEXT_DOCUMENT_CODE_ACTION, lsp.CodeActionOptions(code_action_kinds=[lsp.CodeActionKind.QuickFix])
    )
    @answer("code actions")
    def actions(ls: RoboscServer, params: lsp.CodeActionParams) -> list[lsp.CodeAction] | None:
        return code_actions(params.text_document.uri, list(params.context.diagnostics))

    @server.feature(lsp.TEXT_DOCUMENT_FORMATTING)
    @answer("formatting")
    def formatting(ls: RoboscServer, params: lsp.DocumentFormattingParams) -> list[lsp.TextEdit] | None:
        from robosc.api import format_text

        document = ls.workspace.get_text_document(params.text_document.uri)
        formatted = format_text(document.source, ls.path_of(document.uri))
        if not isinstance(formatted, str):  # it does not parse: nothing to do
            return None
        if formatted == document.source:
            return []
        end = lsp.Position(line=len(document.source.splitlines(keepends=True)), character=0)
        return [lsp.TextEdit(range=lsp.Range(start=lsp.Position(line=0, character=0), end=end), new_text=formatted)]

    return server


def serve(search_paths: Sequence[str] = ()) -> Any:
    """Run the server on standard input and output until the client ends it."""
    return create(search_paths).start_io()
