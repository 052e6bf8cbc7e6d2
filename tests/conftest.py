from __future__ import annotations

import os
import sys
import uuid
from pathlib import Path
from typing import Any

import pytest
from xdist.scheduler import LoadScopeScheduling

import strays
from robosc.api import CheckResult, check_file

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def pytest_configure(config: pytest.Config) -> None:
    """Mark the suite's environment, inherited by every process a test starts (see strays.py);
    .ci/run may have set the mark already, to check again after pytest exits."""
    os.environ.setdefault(strays.MARK, uuid.uuid4().hex)
    # GNU readline (which pytest imports) writes COLUMNS=80 into the process's environment,
    # where os.environ does not see it but subprocesses do; robosc fits its output to COLUMNS,
    # and the tests read it as piped (tests that want a width set COLUMNS themselves)
    os.environ.pop("COLUMNS", None)
    os.unsetenv("COLUMNS")


# The tests that start middleware, nodes, browsers or simulations paced in real time: with
# pytest-xdist (`-n 2`, pyproject's addopts) they all run in one worker, one at a time as without
# xdist (their ROS domains and ports are those of one process), while the other worker takes the
# tests that only compute. The scheduler below groups them by their file's name (pytest-xdist's
# own xdist_group mark is lost on pytest 9, which no longer reads the node id xdist rewrites).
MIDDLEWARE = {
    "test_belief", "test_boundary_ros", "test_build", "test_codegen_ros", "test_docs", "test_faults_ros",
    "test_fleet_ros", "test_fleet_world_ros", "test_live_server", "test_live_view", "test_ros1", "test_ros2",
    "test_ros_support", "test_sim_ros", "test_sim_view", "test_fleet_view",
}
_oracle_lines: list[str] = []  # the oracle's summary, as the xdist workers hand it over


class MiddlewareInOneWorker(LoadScopeScheduling):  # type: ignore[misc]
    """pytest-xdist's scheduler that hands each unit of work to one worker whole: every test of
    a MIDDLEWARE file is in one unit, any other test is a unit of its own."""

    def _split_scope(self, nodeid: str) -> str:
        return "middleware" if Path(nodeid.split("::", 1)[0]).stem in MIDDLEWARE else nodeid


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_make_scheduler(config: pytest.Config, log: Any) -> MiddlewareInOneWorker:
    return MiddlewareInOneWorker(config, log)


def _oracle_summary() -> list[str]:
    oracle = sys.modules.get("test_oracle")
    return oracle.summary() if oracle is not None else []


@pytest.hookimpl(optionalhook=True)
def pytest_testnodedown(node: Any, error: Any) -> None:
    """A pytest-xdist worker ended: keep what it saw of the oracle."""
    _oracle_lines.extend(getattr(node, "workeroutput", {}).get("oracle", []))


def pytest_terminal_summary(terminalreporter: Any) -> None:
    """What the random-model oracle met (tests/test_oracle.py), when it ran."""
    for line in _oracle_lines + _oracle_summary():
        terminalreporter.write_line(line)


def pytest_sessionfinish(session: pytest.Session, exitstatus: int) -> None:
    """A process a test started that is still running at the end fails the run."""
    if hasattr(session.config, "workerinput"):
        session.config.workeroutput["oracle"] = _oracle_summary()  # type: ignore[attr-defined]
        return  # a pytest-xdist worker: the controller checks, once
    left = strays.strays(os.environ[strays.MARK])
    if left:
        session.config.get_terminal_writer().line("\n" + strays.report(left), red=True)
        session.exitstatus = pytest.ExitCode.TESTS_FAILED


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item: pytest.Item, call: pytest.CallInfo[None]) -> Any:
    """A failing test that started ROS processes shows what they printed (the nodes' logs are
    otherwise lost with the test's temporary folder, and a CI failure must be readable)."""
    outcome = yield
    report = outcome.get_result()
    if report.when != "call" or not report.failed:
        return
    for name in ("ros1", "ros2"):
        middleware = getattr(item, "funcargs", {}).get(name)
        processes = getattr(middleware, "processes", None)
        if processes is not None:
            report.sections.append(("processes of " + name, processes.output()))


@pytest.fixture(autouse=True)
def _ros_home(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Every test has a ROS home of its own: the nodes it starts log there (never in the user's
    ~/.ros), and no test sees another's files."""
    monkeypatch.setenv("ROS_HOME", str(tmp_path / "ros_home"))


def codes(result: CheckResult) -> list[str]:
    return [d.code for d in result.diagnostics]


def messages(result: CheckResult) -> str:
    return "\n".join(d.message for d in result.diagnostics)


@pytest.fixture
def check(tmp_path: Path):
    """check(robot_text, **libraries) -> CheckResult; libraries are written next to the robot."""

    def run(text: str, **libraries: str) -> CheckResult:
        for name, lib in libraries.items():
            (tmp_path / f"{name}.rscd").write_text(lib, encoding="utf-8")
        path = tmp_path / "model.rscd"
        path.write_text(text, encoding="utf-8")
        return check_file(path)

    return run


def robot(*body: str) -> str:
    """A robot around ``body`` with one valid component to refer to."""
    return (
        "robot R {\n"
        "  component S {\n"
        "    outgoing message sense with type: boolean\n"
        "    incoming message act with type: none\n"
        "    behaviour {\n"
        "      variable active: boolean = false\n"
        "      on response from sense do active := value\n"
        "      initial marked state idle { on request to act goto busy }\n"
        "      state busy { transition goto idle }\n"
        "    }\n"
        "  }\n" + "\n".join(body) + "\n}\n"
    )


sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "benchmarks"))  # the model families


# real-ROS fixtures (tests/ros_support.py)
from ros_support import ros1, ros2  # noqa: E402, F401
