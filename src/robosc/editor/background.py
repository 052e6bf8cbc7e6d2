"""Synthesis for hover, in a process of its own: it never holds the server's interpreter
(a large model's synthesis takes minutes), it starts only once typing has paused, and a
newer version of the model stops the run for an older one."""

from __future__ import annotations

import asyncio
import logging
import multiprocessing
from collections.abc import Callable, Sequence
from multiprocessing.connection import Connection
from typing import Any

log = logging.getLogger(__name__)
IDLE_SECONDS = 0.75  # typing paused this long: synthesize


def _job(text: str, path: str, search_paths: Sequence[str], send: Connection) -> None:
    """In the child: check and synthesize ``text``, send the hover notes (or None)."""
    import os

    os.nice(10)  # the server and the editor come first
    from robosc.api import check_text, synthesize_model
    from robosc.editor.hover import guard_notes

    try:
        checked = check_text(text, path, search_paths)
        notes = guard_notes(synthesize_model(checked.model)) if checked.model is not None else None
    except Exception:  # the parent logs that nothing came
        notes = None
    send.send(notes)
    send.close()


class Synthesizer:
    """One synthesis at a time per document; the newest version wins."""

    def __init__(self, deliver: Callable[[str, Any, dict[str, list[str]] | None], None]) -> None:
        self.deliver = deliver  # (uri, version token, notes)
        self.context = multiprocessing.get_context("spawn")  # no fork of a threaded server
        self.running: dict[str, tuple[Any, Connection]] = {}
        self.waiting: dict[str, asyncio.TimerHandle] = {}

    def request(self, uri: str, token: Any, text: str, path: str, search_paths: Sequence[str]) -> None:
        """Synthesize this version of ``uri`` once typing has paused (stopping an older run)."""
        old = self.waiting.pop(uri, None)
        if old is not None:
            old.cancel()
        loop = asyncio.get_event_loop()
        self.waiting[uri] = loop.call_later(IDLE_SECONDS, self._start, uri, token, text, path, list(search_paths))

    def stop(self, uri: str) -> None:
        waiting = self.waiting.pop(uri, None)
        if waiting is not None:
            waiting.cancel()
        running = self.running.pop(uri, None)
        if running is not None:
            process, receive = running
            asyncio.get_event_loop().remove_reader(receive.fileno())
            process.terminate()
            process.join(5)
            receive.close()

    def stop_all(self) -> None:
        for uri in list(self.waiting) + list(self.running):
            self.stop(uri)

    def _start(self, uri: str, token: Any, text: str, path: str, search_paths: list[str]) -> None:
        self.waiting.pop(uri, None)
        self.stop(uri)
        receive, send = self.context.Pipe(duplex=False)
        process = self.context.Process(target=_job, args=(text, path, search_paths, send), daemon=True)
        process.start()
        send.close()
        self.running[uri] = (process, receive)
        asyncio.get_event_loop().add_reader(receive.fileno(), self._finished, uri, token)

    def _finished(self, uri: str, token: Any) -> None:
        process, receive = self.running.pop(uri)
        asyncio.get_event_loop().remove_reader(receive.fileno())
        try:
            notes = receive.recv()
        except (EOFError, OSError):
            log.warning("synthesis of %s ended without a result", uri)
            notes = None
        receive.close()
        process.join(5)
        if notes is not None:
            self.deliver(uri, token, notes)
