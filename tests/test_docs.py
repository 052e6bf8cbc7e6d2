"""The documentation cannot drift from the tool: the site builds in strict mode (a warning or a
broken link fails), every model in it checks as its first line says, every check code has a
model that gets it, every `robosc` command shown runs and prints what the page shows, and the
deploy pages give the steps of the READMEs that `robosc build` writes (which test_build.py
follows literally on real ROS)."""

from __future__ import annotations

import json
import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

from ros_support import ros2_available, unavailable

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
PAGES = sorted(DOCS.rglob("*.md"))
MODELS = sorted([*DOCS.glob("models/*.rscd"), *DOCS.glob("rules/*.rscd")])
EXPECT = re.compile(r"// expect: (\S+)(?: \((synthesize|build)\))?$")


def robosc(*args: str, cwd: Path, timeout: float = 300, stdin: str = "") -> subprocess.CompletedProcess[str]:
    env = {k: v for k, v in os.environ.items() if k != "COLUMNS"}
    return subprocess.run(
        [sys.executable, "-m", "robosc", *args], cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout,
        input=stdin,
    )


def test_the_site_builds_in_strict_mode(tmp_path: Path) -> None:
    mkdocs = Path(sys.executable).parent / "mkdocs"
    if not mkdocs.exists():
        unavailable("MkDocs (pip install -e '.[docs]')")
    done = subprocess.run(
        [str(mkdocs), "build", "--strict", "-d", str(tmp_path / "site")], cwd=ROOT, capture_output=True, text=True, timeout=300
    )
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    codes = (tmp_path / "site" / "codes" / "index.html").read_text()
    assert "package-name" in codes and "uncontrollable-requirement" in codes  # made from the registry
    cli = (tmp_path / "site" / "cli" / "index.html").read_text()
    for command in ("check", "synthesize", "simulate", "build", "sim", "view", "lsp"):
        assert f"robosc {command} [OPTIONS]" in cli, command  # made from the commands' help
    assert "Sentinel" not in cli
    api = (tmp_path / "site" / "api" / "index.html").read_text()
    assert "check_file" in api and "synthesize_model" in api  # made from the docstrings


@pytest.mark.parametrize("model", MODELS, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_every_model_in_the_docs_gets_what_it_says(model: Path, tmp_path: Path) -> None:
    first = model.read_text().splitlines()[0]
    found = EXPECT.match(first)
    assert found, f"{model}: the first line says what the model gets: '// expect: ok' or '// expect: CODE'"
    expected, how = found.group(1), found.group(2) or "check"
    if how == "build":
        done = robosc("build", str(model), "-o", str(tmp_path / "out"), cwd=ROOT)
        assert done.returncode == 1 and ": error: " in done.stderr, done.stderr
        return
    if how == "synthesize":
        done = robosc("synthesize", "--json", str(model), cwd=ROOT)
        codes = {w["code"] for w in json.loads(done.stdout)["warnings"]}
    else:
        done = robosc("check", "--format", "json", str(model), cwd=ROOT)
        codes = {d["code"] for d in json.loads(done.stdout)}
    if expected == "ok":
        assert done.returncode == 0 and not codes, done.stdout + done.stderr
    else:
        assert expected in codes, (codes, done.stderr)


def test_every_check_code_has_a_model_that_gets_it() -> None:
    from robosc.language.codes import Code

    missing = [c.value for c in Code if c.value != "io" and not (DOCS / "rules" / f"{c.value}.rscd").exists()]
    assert not missing, f"no model in docs/rules/ for {missing}"
    for rule in (DOCS / "rules").glob("*.rscd"):
        assert rule.stem in {c.value for c in Code}, rule  # no model for a code that is gone


def test_models_written_in_the_pages_are_included_files() -> None:
    """A robosc block on a page is a file of docs/models or docs/rules (which the test above
    checks), included with --8<--; the codes page's blocks are put there from docs/rules."""
    for page in PAGES:
        for block in re.findall(r"```robosc\n(.*?)```", page.read_text(), re.S):
            assert block.strip().startswith('--8<-- "docs/'), f"{page.name}: a model written in the page:\n{block}"


def console_blocks() -> list[tuple[str, int, str, list[str], int]]:
    """(page, block number, command, the output shown, the exit status shown) for each
    `$ robosc ...` line of the pages' console blocks."""
    found = []
    for page in PAGES:
        text = page.read_text()
        for number, match in enumerate(re.finditer(r"(?:<!-- exit: (\d+) -->\n)?```console\n(.*?)```", text, re.S)):
            status = int(match.group(1) or 0)
            command, shown = None, []
            for line in match.group(2).splitlines():
                if line.startswith("$ "):
                    if command is not None:
                        found.append((page.relative_to(DOCS).as_posix(), number, command, shown, status))
                    command, shown = line[2:], []
                else:
                    shown.append(line)
            if command is not None:
                found.append((page.relative_to(DOCS).as_posix(), number, command, shown, status))
    return found


COMMANDS = console_blocks()


def test_the_pages_show_commands() -> None:
    assert len(COMMANDS) >= 10
    assert all(command.startswith("robosc ") for _, _, command, _, _ in COMMANDS)


@pytest.mark.parametrize(("page", "number", "command", "shown", "status"), COMMANDS, ids=lambda v: str(v)[:40])
def test_a_command_in_the_docs_prints_what_the_page_shows(
    tmp_path: Path, page: str, number: int, command: str, shown: list[str], status: int
) -> None:
    """Run from a folder holding the repository's examples/ and docs/ (outputs go there). Each
    shown line is printed, in order; '...' stands for lines left out, and a line ending in
    '...' for its beginning. A line '> TEXT' is typed at robosc simulate's prompt."""
    if " --ros 2" in command and not ros2_available():
        unavailable("ROS 2 (pip install '.[ros2]')")
    if " sim " in f" {command} ":
        pytest.importorskip("irsim", reason="robosc sim needs IR-SIM")
    for name in ("examples", "docs"):
        (tmp_path / name).symlink_to(ROOT / name)
    typed = "".join(line[2:] + "\n" for line in shown if line.startswith("> "))
    done = robosc(*shlex.split(command)[1:], cwd=tmp_path, stdin=typed)
    assert done.returncode == status, f"{page}: {command}\n{done.stdout[-3000:]}\n{done.stderr[-3000:]}"
    # what was typed is not echoed: the answer follows the prompt on its line
    printed = [re.sub(r"^(> )+", "", line.rstrip()) for line in (done.stdout + done.stderr).splitlines()]
    at = 0
    for line in shown:
        if line.strip() == "..." or line.startswith("> "):
            continue
        wanted = line.rstrip()
        prefix = wanted.endswith("...")
        wanted = wanted[:-3].rstrip() if prefix else wanted
        while at < len(printed) and not (printed[at].startswith(wanted) if prefix else printed[at] == wanted):
            at += 1
        assert at < len(printed), f"{page}: `{command}` did not print, in order:\n{line}\n---\n" + "\n".join(printed)
        at += 1


@pytest.mark.parametrize("ros", [1, 2])
def test_the_deploy_pages_give_the_steps_of_the_generated_readme(tmp_path: Path, ros: int) -> None:
    done = robosc("build", "examples/line_follower.rscd", "-o", str(tmp_path / "out"), cwd=ROOT)
    assert done.returncode == 0, done.stderr
    readme = (tmp_path / f"out/ros{ros}/line_follower_robosc/README.md").read_text()
    page = (DOCS / "howto" / f"ros{ros}.md").read_text()
    steps = re.findall(r"```sh\n(.*?)```", readme, re.S)[0]
    assert steps in re.findall(r"```sh\n(.*?)```", page, re.S), f"howto/ros{ros}.md does not give:\n{steps}"


def python_examples() -> list[tuple[str, int, str, str]]:
    """(page, block number, code, what it prints) for each ```python block of the pages that
    the text says prints a ```text block."""
    found = []
    for page in PAGES:
        text = page.read_text()
        pattern = r"```python\n(.*?)```\n\nprints\n\n```text\n(.*?)```"
        for number, match in enumerate(re.finditer(pattern, text, re.S)):
            found.append((str(page.relative_to(DOCS)), number, match.group(1), match.group(2)))
    return found


PYTHON_EXAMPLES = python_examples()


def test_the_pages_show_python_examples() -> None:
    assert {page for page, *_ in PYTHON_EXAMPLES} >= {"howto/fleet.md"}


@pytest.mark.parametrize(("page", "number", "code", "printed"), PYTHON_EXAMPLES, ids=lambda v: str(v)[:20])
def test_a_python_example_in_the_docs_prints_what_the_page_shows(page: str, number: int, code: str, printed: str) -> None:
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-3000:]
    assert done.stdout == printed, f"{page}, python example {number}:\n{done.stdout}"


def test_list_codes_aligns_every_description() -> None:
    done = robosc("check", "--list-codes", cwd=ROOT)
    lines = done.stdout.splitlines()
    starts = {len(line) - len(line.split(None, 1)[1]) for line in lines}
    assert len(starts) == 1, lines  # one column, even for the longest code


def test_readme_points_to_the_documentation_inside_the_repository() -> None:
    text = (ROOT / "README.md").read_text()
    assert "../shared" not in text
    assert "docs/language.md" in text and "docs/tutorial.md" in text
