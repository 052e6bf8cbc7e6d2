# -*- coding: utf-8 -*-
"""The live view's web server: the page, and every event as a Server-Sent Event.

Standard library only and Python 3.8 compatible: ``robosc generate`` copies this
file into the ROS packages (as ``robosc_live.py``), so a node on the robot serves
the page itself with nothing to install. Binds 127.0.0.1 unless told otherwise.

    view = LiveView(page_html, port=8765)   # serves in a thread of its own
    view.publish({"time": ..., "event": ..., "controllable": ..., "data": ..., "state": {...}})

Every open page gets a pulse each half second saying how long ago the data last came
(``watched``: a view of a robot elsewhere, whose heartbeat ``alive()`` records; otherwise the
source is this process, alive while it serves) and whether the run ended (``end()``), so that
the page never shows old data as live.
"""

from __future__ import print_function

import json
import queue
import threading
import time
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any, Dict, List, Optional, Union

PULSE_SECONDS = 0.5  # how often an open page hears whether data still comes (and the connection is kept)
QUEUE_SIZE = 2000  # events kept for a slow browser; older ones are dropped
BACKLOG = 512  # connections waiting to be accepted: 200 pages opening at once are all taken at once
LOCAL_HOSTS = ("127.0.0.1", "localhost", "[::1]")  # the Host header a page on this machine sends


def local_host(header: Optional[str]) -> bool:
    """Whether a request's Host header names this machine's loopback (with any port): a page
    from elsewhere that re-binds its own name to 127.0.0.1 (DNS rebinding) is refused."""
    if not header:
        return False
    host = header.strip().lower()
    if host.startswith("["):
        name = host[: host.find("]") + 1] if "]" in host else host
    else:
        name = host.rsplit(":", 1)[0] if host.count(":") == 1 else host
    return name in LOCAL_HOSTS


class _Server(ThreadingHTTPServer):
    request_queue_size = BACKLOG
    daemon_threads = True


class LiveView(object):
    def __init__(
        self, page: Union[str, bytes], port: int = 8765, host: str = "127.0.0.1", watched: bool = False
    ) -> None:
        self.page = page.encode("utf-8") if not isinstance(page, bytes) else page
        self.watched = watched
        self.heard = time.monotonic()  # when the data last came (or the robot said it is there)
        self.ended = None  # type: Optional[str]
        self.clients: "List[queue.Queue[str]]" = []
        self.lock = threading.Lock()
        self.last: "Optional[Dict[str, Any]]" = None  # the latest record: a new browser starts from it
        self.dropped = 0
        view = self

        class Handler(BaseHTTPRequestHandler):
            def log_message(self, format: str, *args: Any) -> None:  # quiet
                pass

            def do_GET(self) -> None:
                if not local_host(self.headers.get("Host")):
                    self.send_error(403, "the live view answers only to 127.0.0.1 and localhost")
                    return
                path = self.path.split("?", 1)[0]
                if path in ("/", "/index.html"):
                    self.send_response(200)
                    self.send_header("Content-Type", "text/html; charset=utf-8")
                    self.send_header("Content-Length", str(len(view.page)))
                    self.send_header("Cache-Control", "no-store")
                    self.end_headers()
                    self.wfile.write(view.page)
                elif path == "/events":
                    view.stream(self)
                elif path == "/state":
                    body = json.dumps(view.last).encode("utf-8")
                    self.send_response(200)
                    self.send_header("Content-Type", "application/json")
                    self.send_header("Content-Length", str(len(body)))
                    self.end_headers()
                    self.wfile.write(body)
                else:
                    self.send_error(404)

        self.server = _Server((host, port), Handler)
        self.port = self.server.server_address[1]
        self.thread = threading.Thread(target=self.server.serve_forever, name="robosc-live-view")
        self.thread.daemon = True
        self.thread.start()

    @property
    def url(self) -> str:
        return "http://%s:%d/" % (str(self.server.server_address[0]), self.port)

    def alive(self) -> None:
        """The source is there (a robot's heartbeat), though nothing happened."""
        self.heard = time.monotonic()

    def end(self, why: str) -> None:
        """No more data will come (the run ended): the pages say so."""
        self.ended = why

    def pulse(self) -> bytes:
        """What a page hears every half second (a Server-Sent Event): how old the data is, and
        whether it ended."""
        age = time.monotonic() - self.heard if self.watched else 0.0
        return ("event: pulse\ndata: %s\n\n" % json.dumps({"age": round(age, 1), "ended": self.ended})).encode("utf-8")

    def publish(self, record: Dict[str, Any]) -> None:
        """Send an event record to every open page (never blocks the caller)."""
        text = json.dumps(record, sort_keys=True, default=str)
        self.heard = time.monotonic()
        with self.lock:
            self.last = record
            clients = list(self.clients)
        for q in clients:
            try:
                q.put_nowait(text)
            except queue.Full:
                self.dropped += 1

    def stream(self, handler: BaseHTTPRequestHandler) -> None:
        q: "queue.Queue[str]" = queue.Queue(QUEUE_SIZE)
        with self.lock:
            self.clients.append(q)
            last = self.last
        try:
            handler.send_response(200)
            handler.send_header("Content-Type", "text/event-stream")
            handler.send_header("Cache-Control", "no-store")
            handler.end_headers()
            handler.wfile.write(b"retry: 1000\n\n")
            if last is not None:
                handler.wfile.write(("event: state\ndata: %s\n\n" % json.dumps(last, default=str)).encode("utf-8"))
            handler.wfile.write(self.pulse())
            handler.wfile.flush()
            due = time.monotonic() + PULSE_SECONDS
            while True:
                try:
                    text = q.get(timeout=max(0.0, due - time.monotonic()))
                except queue.Empty:
                    handler.wfile.write(self.pulse())
                    handler.wfile.flush()
                    due = time.monotonic() + PULSE_SECONDS
                    continue
                lines = [text]
                while len(lines) < 200:  # send what piled up in one write
                    try:
                        lines.append(q.get_nowait())
                    except queue.Empty:
                        break
                handler.wfile.write("".join("data: %s\n\n" % t for t in lines).encode("utf-8"))
                handler.wfile.flush()
        except (BrokenPipeError, ConnectionResetError, OSError):
            pass
        finally:
            with self.lock:
                if q in self.clients:
                    self.clients.remove(q)

    def close(self) -> None:
        self.server.shutdown()
        self.server.server_close()
