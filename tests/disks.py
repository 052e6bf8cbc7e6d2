"""Storage that fails, for the storage tests (test_storage_ros.py) and benchmarks/faults.py: tmpfs
mounts made and removed (root), one read-only, one full; and the Fast DDS profiles robosc's
nodes leave in /dev/shm."""

from __future__ import annotations

import contextlib
import os
import subprocess
from collections.abc import Iterator
from pathlib import Path


class CannotMount(Exception):
    """No tmpfs could be mounted (not root)."""


@contextlib.contextmanager
def mounted(folder: Path, options: str) -> Iterator[Path]:
    """A tmpfs at ``folder`` with mount ``options`` (``ro``; ``size=64k``), unmounted afterwards."""
    folder.mkdir(parents=True, exist_ok=True)
    made = subprocess.run(["mount", "-t", "tmpfs", "-o", options, "tmpfs", str(folder)], capture_output=True, text=True)
    if made.returncode != 0:
        raise CannotMount(f"{made.stderr.strip()}: mounting needs root")
    try:
        yield folder
    finally:
        subprocess.run(["umount", "-l", str(folder)], check=False)


@contextlib.contextmanager
def full(folder: Path) -> Iterator[Path]:
    """A 64 KiB tmpfs with no byte left (a ``log`` folder made first, as ROS would find it)."""
    with mounted(folder, "size=64k") as disk:
        (disk / "log").mkdir()
        handle = os.open(disk / "filler", os.O_WRONLY | os.O_CREAT)
        with contextlib.suppress(OSError):
            while os.write(handle, b"\0" * 4096):
                pass
        os.close(handle)
        yield disk


def profiles() -> set[str]:
    """The Fast DDS profiles robosc's nodes wrote to /dev/shm."""
    return {name for name in os.listdir("/dev/shm") if name.startswith("robosc-fastdds")}
