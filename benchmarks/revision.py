"""Another revision of robosc for a benchmark to run beside this one: its source tree (from git)
and the packages it generates."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def source_tree(revision: str, work: Path) -> Path:
    """``src`` of ``revision``, unpacked under ``work`` (once)."""
    tree = work / f"robosc-{revision}"
    if not tree.exists():
        archive = subprocess.run(["git", "-C", str(ROOT), "archive", revision, "src"], capture_output=True, check=True)
        tree.mkdir(parents=True)
        subprocess.run(["tar", "-x", "-C", str(tree)], input=archive.stdout, check=True)
    return tree / "src"


def generate(model: Path, ros: int, out: Path, revision: str | None, work: Path) -> Path:
    """``robosc generate --ros ROS MODEL -o OUT`` by this robosc, or by ``revision``'s."""
    env = dict(os.environ)
    if revision is not None:
        env["PYTHONPATH"] = str(source_tree(revision, work))
    subprocess.run(
        [sys.executable, "-m", "robosc", "generate", "--ros", str(ros), str(model), "-o", str(out)],
        env=env,
        check=True,
        capture_output=True,
    )
    return out
