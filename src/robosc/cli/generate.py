"""``robosc generate FILE --ros 1|2 --mode controller|supervisor -o DIR`` and ``robosc build FILE -o DIR``."""

from __future__ import annotations

from pathlib import Path

import click

from robosc.cli.common import (
    EXIT_MODEL_ERRORS,
    EXIT_OK,
    exit_with,
    include_option,
    input_problem,
    instances_option,
    say,
    width,
)
from robosc.cli.results import supervised

MODE = click.option(
    "--mode",
    type=click.Choice(["controller", "supervisor"]),
    default="controller",
    show_default=True,
    help="controller: the node drives the robot; supervisor: a supervision layer between an existing controller and the robot.",
)


def live_page(result: object) -> str | None:
    """The live view's page, or None (with a note) when Graphviz is not installed."""
    from robosc.debug.layout import LayoutError
    from robosc.debug.live import live_page as page_of

    try:
        return page_of(result)  # type: ignore[arg-type]
    except LayoutError as exc:
        say(f"robosc: note: no live view page in the package (Graphviz: {exc})", err=True)
        return None


RELATIVE = click.option(
    "--relative-names",
    is_flag=True,
    help="Make the model's absolute ROS names relative (/scan -> scan), so that a namespace "
    "(__ns on ROS 2, the launch file's namespace argument) moves the whole robot.",
)


def _write_package(
    plan: object,
    ros: int,
    mode: str,
    output: Path,
    file: str,
    include: tuple[str, ...],
    page: str | None = None,
    relative: bool = False,
) -> list[Path]:
    from robosc.codegen.ros import RosError
    from robosc.codegen.ros import generate as generate_package

    try:
        return generate_package(plan, ros, mode, output, page, relative)  # type: ignore[arg-type]
    except RosError as exc:
        from robosc.api import check_file
        from robosc.language.codes import Code
        from robosc.language.diagnostics import error, render_text

        sources = check_file(file, include).sources
        click.echo(render_text(error(exc.span, str(exc), Code.ROS), sources, width(err=True)), err=True)
        raise exit_with(EXIT_MODEL_ERRORS) from None
    except OSError as exc:
        raise input_problem(f"{output}: cannot write: {exc.strerror or exc}") from None


@click.command()
@click.argument("file", type=click.Path())
@click.option(
    "--ros",
    type=click.Choice(["1", "2"]),
    required=True,
    help="ROS generation: 1 (catkin, rospy) or 2 (ament_python, rclpy).",
)
@MODE
@click.option(
    "-o", "--output", type=click.Path(file_okay=False), required=True, help="Directory to write the package to."
)
@RELATIVE
@include_option
@instances_option
def generate(
    file: str, ros: str, mode: str, output: str, relative_names: bool, include: tuple[str, ...], sizes: dict[str, int]
) -> None:
    """Generate a ROS package running the synthesized supervisor."""
    result, plan = supervised(file, include, "code generation", sizes, warn=True)
    written = _write_package(plan, int(ros), mode, Path(output), file, include, live_page(result), relative_names)
    say(f"wrote ROS {ros} package ({mode}) to {output}: {len(written)} files")
    raise exit_with(EXIT_OK)


@click.command()
@click.argument("file", type=click.Path())
@click.option("-o", "--output", type=click.Path(file_okay=False), required=True, help="Directory for everything built.")
@MODE
@RELATIVE
@include_option
@instances_option
def build(
    file: str, output: str, mode: str, relative_names: bool, include: tuple[str, ...], sizes: dict[str, int]
) -> None:
    """Check, synthesize, and write everything: the ROS 1 and ROS 2 packages, the
    stand-alone supervisor module (with the runtime it needs) and the CIF file."""
    from robosc.codegen.cif import to_cif
    from robosc.codegen.module import RUNTIME_PACKAGE, module_name, render_module, runtime_files
    from robosc.codegen.ros import package_name

    result, plan = supervised(file, include, "a build", sizes, warn=True)
    out = Path(output)
    say(
        f"{plan.robot}: supervisor synthesized in {result.seconds:.3f} s, "
        f"{result.reachable_states:,} reachable states, {len(result.added_guards)} added guards"
    )
    page = live_page(result)
    for ros in (1, 2):  # ros1/ and ros2/ are like a workspace's src/: the folder is the package's name
        target = out / f"ros{ros}" / package_name(plan)
        written = _write_package(plan, ros, mode, target, file, include, page, relative_names)
        say(f"  ROS {ros} package ({mode}): {target}  ({len(written)} files)")
    try:
        module = out / f"{module_name(plan)}.py"
        module.write_text(render_module(plan, relative_names), encoding="utf-8")
        (out / RUNTIME_PACKAGE).mkdir(exist_ok=True)
        for name, text in runtime_files().items():
            (out / RUNTIME_PACKAGE / name).write_text(text, encoding="utf-8")
        say(f"  stand-alone supervisor: {module} (runtime: {out / RUNTIME_PACKAGE})")
        cif_path = out / f"{plan.robot}.cif"
        cif_path.write_text(to_cif(result.network, Path(file).name), encoding="utf-8")
        say(f"  CIF: {cif_path}")
    except OSError as exc:
        raise input_problem(f"{output}: cannot write: {exc.strerror or exc}") from None
    raise exit_with(EXIT_OK)
