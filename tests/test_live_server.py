"""The live view's server (copied onto robots): loopback Host headers only, and many pages
at once without waiting."""

from __future__ import annotations

import http.client
import socket
import statistics
import threading
import time

import pytest

from robosc.runtime.onboard.live_server import LiveView, local_host


def get(port: int, path: str, host: str) -> tuple[int, bytes]:
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=5)
    connection.putrequest("GET", path, skip_host=True)
    connection.putheader("Host", host)
    connection.endheaders()
    response = connection.getresponse()
    body = response.read() if path != "/events" else b""
    connection.close()
    return response.status, body


@pytest.fixture
def view() -> LiveView:
    live = LiveView("<html>page</html>", port=0)
    live.publish({"event": "e", "state": {}})
    yield live
    live.close()


def test_only_loopback_host_headers_are_answered(view: LiveView) -> None:
    port = view.port
    for host in (f"127.0.0.1:{port}", f"localhost:{port}", "localhost", f"[::1]:{port}", "LOCALHOST"):
        assert get(port, "/", host) == (200, b"<html>page</html>"), host
    for host in ("evil.example.com", f"evil.example.com:{port}", "127.0.0.1.evil.com", "", "localhost.evil:80"):
        status, _ = get(port, "/state", host)
        assert status == 403, host
    assert local_host("127.0.0.1") and not local_host(None)


def test_two_hundred_pages_at_once_are_served_without_waiting(view: LiveView) -> None:
    """200 clients open the event stream at the same moment: each gets its first bytes
    within a second (the listen backlog takes them all)."""
    port = view.port
    waits: list[float] = []
    failures: list[str] = []
    start = threading.Event()
    lock = threading.Lock()
    sockets: list[socket.socket] = []

    def client() -> None:
        start.wait()
        began = time.monotonic()
        try:
            s = socket.create_connection(("127.0.0.1", port), timeout=10)
            s.sendall(f"GET /events HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\r\n".encode())
            data = b""
            while b"retry:" not in data:
                chunk = s.recv(4096)
                if not chunk:
                    break
                data += chunk
            with lock:
                waits.append(time.monotonic() - began)
                sockets.append(s)
        except OSError as error:
            with lock:
                failures.append(str(error))

    threads = [threading.Thread(target=client) for _ in range(200)]
    for thread in threads:
        thread.start()
    start.set()
    for thread in threads:
        thread.join(30)
    try:
        assert failures == []
        assert len(waits) == 200
        assert max(waits) < 1.0, (statistics.median(waits), max(waits))
        view.publish({"event": "after", "state": {}})  # every page gets the next event
        got = 0
        for s in sockets:
            s.settimeout(5)
            data = b""
            while b'"after"' not in data:
                chunk = s.recv(65536)
                if not chunk:
                    break
                data += chunk
            got += b'"after"' in data
        assert got == 200
    finally:
        for s in sockets:
            s.close()
