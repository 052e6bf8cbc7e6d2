"""Processes robosc starts end with it.

Each child gets a process group of its own (so a terminal's Ctrl-C reaches robosc alone and
robosc ends its children in order, and whatever a child starts in turn ends with it), and is
asked by the kernel to end when robosc dies without a chance to clean up (``kill -9``; Linux's
parent-death signal). :func:`ending_on_signals` turns SIGTERM and SIGHUP into the same clean
exit as Ctrl-C, so ``finally`` blocks stop the children.
"""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
import time
from collections.abc import Iterator, Sequence
from typing import Any

PR_SET_PDEATHSIG = 1


def _prctl() -> Any:
    """Linux's prctl, loaded before forking (nothing may be loaded between fork and exec)."""
    if sys.platform.startswith("linux"):
        import ctypes

        with contextlib.suppress(OSError, AttributeError):
            return ctypes.CDLL(None, use_errno=True).prctl
    return None


class Terminated(KeyboardInterrupt):
    """SIGTERM or SIGHUP arrived: unwound like Ctrl-C; ``signum`` says which."""

    def __init__(self, signum: int) -> None:
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


def _own_group(parent: int, prctl: Any) -> None:  # runs in the child between fork and exec
    os.setpgid(0, 0)
    if prctl is not None:
        prctl(PR_SET_PDEATHSIG, signal.SIGTERM)
    if os.getppid() != parent:  # the parent died before the line above: nobody to end us
        os._exit(1)


def start(command: Sequence[str], **popen: Any) -> subprocess.Popen[bytes]:
    """``subprocess.Popen(command, **popen)`` in a process group of its own, ended by the
    kernel when this process dies. Call it from a thread that lives as long as the child (the
    parent-death signal follows the thread that started it)."""
    parent, prctl = os.getpid(), _prctl()
    return subprocess.Popen(list(command), preexec_fn=lambda: _own_group(parent, prctl), **popen)


def _signal_group(process: subprocess.Popen[bytes], sig: int) -> None:
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(process.pid, sig)  # the child's group: it and whatever it started


def stop(processes: Sequence[subprocess.Popen[bytes]], grace: float = 10.0) -> None:
    """End ``processes`` (started by :func:`start`) and their groups: SIGTERM, the last started
    first; SIGKILL to each group still there after ``grace`` seconds. Returns when all ended."""
    for process in reversed(processes):
        _signal_group(process, signal.SIGTERM)
    end = time.monotonic() + grace
    for process in processes:
        with contextlib.suppress(subprocess.TimeoutExpired):
            process.wait(timeout=max(0.0, end - time.monotonic()))
        _signal_group(process, signal.SIGKILL)  # what is left of its group, if anything
        process.wait()


@contextlib.contextmanager
def ending_on_signals(signals: Sequence[int] = (signal.SIGTERM, signal.SIGHUP, signal.SIGINT)) -> Iterator[None]:
    """Within the block, the first of ``signals`` raises :class:`Terminated` (KeyboardInterrupt
    for SIGINT) where the program is, so that ``finally`` blocks end its children; later ones
    are ignored while it cleans up. Only in the main thread (elsewhere: nothing changes)."""
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield
        return
    raised: list[int] = []

    def handler(signum: int, frame: Any) -> None:
        if raised:
            return  # already unwinding: let the clean-up finish
        raised.append(signum)
        if signum == signal.SIGINT:
            raise KeyboardInterrupt
        raise Terminated(signum)

    previous = {s: signal.signal(s, handler) for s in signals}
    try:
        yield
    finally:
        for s, old in previous.items():
            signal.signal(s, old)
