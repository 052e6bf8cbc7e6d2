"""Processes that outlive the test suite.

The suite marks its environment with ``ROBOSC_TEST_SESSION`` (conftest.py); every process a
test starts inherits it unless the test builds an environment from nothing. At the end, any
process still carrying the mark, other than the suite itself and its ancestors, is a stray:
it is listed, ended (with its process group), and the run fails.

``python tests/strays.py MARK`` does the same check from outside, after pytest has exited
(``.ci/run``); exit status 1 when it found any.
"""

from __future__ import annotations

import contextlib
import os
import signal
import sys
import time
from pathlib import Path

MARK = "ROBOSC_TEST_SESSION"


def _ancestors() -> set[int]:
    found, pid = set(), os.getpid()
    while pid > 1:
        found.add(pid)
        try:
            fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
        except OSError:
            break
        pid = int(fields[1])
    return found


def marked(mark: str, variable: str = MARK) -> dict[int, str]:
    """pid -> command line of every process (but this one and its ancestors) whose environment
    carries ``variable=mark``."""
    needle = f"{variable}={mark}".encode()
    mine = _ancestors()
    found = {}
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit() or int(entry.name) in mine:
            continue
        try:
            if needle not in (entry / "environ").read_bytes().split(b"\0"):
                continue
            if (entry / "stat").read_text().rsplit(")", 1)[1].split()[0] == "Z":
                continue  # a zombie: ended, only not reaped yet
            command = (entry / "cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace").strip()
        except OSError:
            continue  # ended meanwhile
        found[int(entry.name)] = command
    return found


def strays(mark: str, grace: float = 5.0, variable: str = MARK) -> dict[int, str]:
    """The marked processes still there after ``grace`` seconds; they are then killed."""
    end = time.monotonic() + grace
    while (left := marked(mark, variable)) and time.monotonic() < end:
        time.sleep(0.2)
    for pid in left:
        with contextlib.suppress(OSError):
            group = os.getpgid(pid)
            if group != os.getpgid(0):  # its own group: what it started too
                os.killpg(group, signal.SIGKILL)
            else:
                os.kill(pid, signal.SIGKILL)
    return left


def report(left: dict[int, str]) -> str:
    lines = [f"{len(left)} process(es) outlived the tests (now killed):"]
    lines += [f"  {pid}: {command[:200]}" for pid, command in sorted(left.items())]
    return "\n".join(lines)


if __name__ == "__main__":
    left = strays(sys.argv[1])
    if left:
        print(report(left), file=sys.stderr)
    sys.exit(1 if left else 0)
