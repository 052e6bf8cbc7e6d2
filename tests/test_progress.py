"""Long synthesis shows how far it is on a terminal, keeps pipes and --json clean, and stops at
once on Ctrl-C (issue 30, item 4)."""

from __future__ import annotations

import itertools
import os
import pty
import select
import signal
import subprocess
import sys
import time
import types
from pathlib import Path

import pytest

from families import ring
from robosc.api import load_model
from robosc.plant import build_network
from robosc.synthesis import progress
from robosc.synthesis.progress import PHASES, Progress, Watch
from robosc.synthesis.symbolic import synthesize_monolithic

ROOT = Path(__file__).resolve().parent.parent


def test_a_watch_is_told_each_phase_in_order_and_every_step_with_the_same_supervisor(tmp_path: Path) -> None:
    model_file = tmp_path / "ring.rscd"
    model_file.write_text(ring(3))
    network = build_network(load_model(model_file))
    seen: list[Progress] = []
    watch = Watch(seen.append, every=0.0)
    watched = synthesize_monolithic(network, watch=watch)
    alone = synthesize_monolithic(network)
    assert [(g.event.name, g.added) for g in watched.guards] == [(g.event.name, g.added) for g in alone.guards]
    phases = [p.phase for p in seen]
    order = [phase for i, phase in enumerate(phases) if i == 0 or phases[i - 1] != phase]
    assert order[:2] == ["encoding", "bad states"] and order[-2:] == ["reachable", "conditions"]
    assert set(order) <= set(PHASES)
    rounds = [p.round for p in seen if p.phase == "nonblocking"]
    assert rounds and rounds == sorted(rounds) and rounds[0] == 1
    effort: dict[str, int] = watched.effort  # type: ignore[assignment]
    assert seen[-1].steps == effort["images"] + effort["preimages"]  # every image and preimage
    assert all(a.steps <= b.steps and a.seconds <= b.seconds for a, b in itertools.pairwise(seen))
    assert all(p.live_nodes > 0 for p in seen if p.phase != "encoding")


def test_a_watch_says_nothing_before_its_interval_has_passed() -> None:
    seen: list[Progress] = []
    watch = Watch(seen.append, every=3600.0)
    for _ in range(1000):
        watch.step()
    watch.phase("nonblocking", 2)
    assert seen == []


def test_a_watch_counts_the_nodes_in_use_once_a_phase_and_every_few_seconds_not_at_each_report(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # counting walks CUDD's tables: read at every report, it made a ring of 16 robots 4.5x slower
    now = [0.0]  # the watch's clock, moved by hand (the test does not depend on how fast it runs)
    monkeypatch.setattr(progress, "time", types.SimpleNamespace(monotonic=lambda: now[0]))
    counts: list[int] = []

    def count() -> int:
        counts.append(100 + len(counts))
        return counts[-1]

    seen: list[Progress] = []
    watch = Watch(seen.append, every=0.0)
    watch.nodes = count
    for _ in range(500):
        watch.step()
    now[0] = 0.5
    watch.phase("nonblocking", 1)
    for _ in range(500):
        watch.step()
    now[0] = 0.5 + progress.NODES_EVERY
    watch.step()
    assert len(seen) == 1002 and counts == [100, 101, 102]
    assert {p.live_nodes for p in seen[:500]} == {100} and {p.live_nodes for p in seen[500:1001]} == {101}
    assert seen[-1].live_nodes == 102


def _on_a_terminal(args: list[str], until: bytes, seconds: float) -> tuple[subprocess.Popen[bytes], bytes]:
    """``robosc args`` with its standard error on a pseudo-terminal (standard output piped); what
    it printed there until ``until`` appeared (or it ended, or ``seconds`` passed)."""
    leader, follower = pty.openpty()
    process = subprocess.Popen(
        [sys.executable, "-m", "robosc", *args], stdout=subprocess.PIPE, stderr=follower, start_new_session=True
    )
    os.close(follower)
    seen = b""
    end = time.monotonic() + seconds
    while until not in seen and time.monotonic() < end:
        ready, _, _ = select.select([leader], [], [], 0.2)
        if ready:
            try:
                chunk = os.read(leader, 4096)
            except OSError:  # the process ended: the terminal is gone
                break
            seen += chunk
        elif process.poll() is not None:
            break
    os.close(leader)
    return process, seen


@pytest.fixture(scope="module")
def slow_ring(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A ring of 8 robots synthesized monolithically: minutes of BDD work, seconds per preimage."""
    path = tmp_path_factory.mktemp("progress") / "ring8.rscd"
    path.write_text(ring(8))
    return path


def test_synthesis_on_a_terminal_shows_its_progress_and_stops_at_once_on_ctrl_c(slow_ring: Path) -> None:
    """Before: no word for minutes, and Ctrl-C waited for the BDD operation under way (1.3 to 2.6
    s measured on this ring; it unwound as a KeyboardInterrupt, exit 130). Now the process ends
    by the signal itself, wherever synthesis is."""
    process, seen = _on_a_terminal(["synthesize", "--fleet", "monolithic", str(slow_ring)], b"BDD nodes", 120)
    try:
        assert b"synthesizing (Ctrl-C stops): " in seen, seen
        os.kill(process.pid, signal.SIGINT)
        assert process.wait(60) == -signal.SIGINT
        assert process.stdout is not None and process.stdout.read() == b""
    finally:
        if process.poll() is None:
            process.kill()
            process.wait()


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGHUP])
def test_synthesis_ends_at_once_on_sigterm_and_sighup(slow_ring: Path, signum: int) -> None:
    process, seen = _on_a_terminal(["synthesize", "--fleet", "monolithic", str(slow_ring)], b"BDD nodes", 120)
    try:
        assert b"synthesizing (Ctrl-C stops): " in seen, seen  # under way
        os.kill(process.pid, signum)
        assert process.wait(60) == -signum
    finally:
        if process.poll() is None:
            process.kill()
            process.wait()


def test_json_and_pipes_stay_clean(tmp_path: Path) -> None:
    model = tmp_path / "ring.rscd"
    model.write_text(ring(6))
    process, seen = _on_a_terminal(["synthesize", "--json", "--fleet", "monolithic", str(model)], b"never", 120)
    assert process.wait(120) == 0
    assert b"synthesizing" not in seen
    piped = subprocess.run(
        [sys.executable, "-m", "robosc", "synthesize", "--fleet", "monolithic", str(model)],
        capture_output=True,
        timeout=120,
    )
    assert piped.returncode == 0 and b"synthesizing" not in piped.stderr + piped.stdout


def test_the_docs_example_runs(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    """docs/synthesis-options.md's progress example, as written (the warehouse is quick: the
    callback may not be called; the result is printed)."""
    page = (ROOT / "docs/synthesis-options.md").read_text()
    section = page[page.index("## Long runs") : page.index("## Fleets")]
    code = section.split("```python\n", 1)[1].split("```", 1)[0]
    monkeypatch.chdir(ROOT)
    exec(compile(code, "synthesis-options.md", "exec"), {})
    assert capsys.readouterr().out.splitlines()[-1] == "True"
