"""The test suite's own ROS set-up: the ROS 2 domain ids of the tests can be set from
outside (ROBOSC_TEST_DOMAIN_BASE, ROBOSC_TEST_DOMAIN_SPAN), and a setting outside the ids
ROS 2 takes stops the run with a clear message."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent


def domains(**settings: str) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, **settings}
    code = "import ros_support; print([ros_support.new_domain() for _ in range(5)])"
    return subprocess.run([sys.executable, "-c", code], cwd=HERE, env=env, capture_output=True, text=True, timeout=60)


def test_the_tests_domain_ids_can_be_set_from_outside() -> None:
    done = domains(ROBOSC_TEST_DOMAIN_BASE="150", ROBOSC_TEST_DOMAIN_SPAN="3")
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "[150, 151, 152, 150, 151]"


def test_domain_ids_outside_what_ros2_takes_are_refused() -> None:
    done = domains(ROBOSC_TEST_DOMAIN_BASE="230", ROBOSC_TEST_DOMAIN_SPAN="10")
    assert done.returncode != 0
    assert "leave the ids 0 to 232" in done.stderr
    done = domains(ROBOSC_TEST_DOMAIN_BASE="ten")
    assert done.returncode != 0 and "a whole number is wanted" in done.stderr


def test_the_tests_that_start_middleware_are_scheduled_in_one_worker() -> None:
    """pytest-xdist hands the scheduler's units to its workers whole: every test of a file in
    conftest.MIDDLEWARE is in the one unit, any other test is a unit of its own."""
    import conftest

    scheduler = object.__new__(conftest.MiddlewareInOneWorker)  # its _split_scope needs no state
    units = {scheduler._split_scope(nodeid) for nodeid in (
        "tests/test_ros2.py::test_a", "tests/test_sim_ros.py::test_b[2]", "tests/test_live_view.py::test_c",
    )}
    assert units == {"middleware"}
    assert scheduler._split_scope("tests/test_fmt.py::test_d") == "tests/test_fmt.py::test_d"
    assert all((HERE / f"{name}.py").is_file() for name in conftest.MIDDLEWARE)
