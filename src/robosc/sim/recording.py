"""What ``robosc sim --record DIR`` leaves besides the nodes' event logs
(``events/robotK.jsonl``): one MCAP file with every robot's pose, LiDAR and events (Foxglove
replays it: ``foxglove.PoseInFrame`` and ``foxglove.LaserScan`` messages in the frame
``world``), a sequence-of-events plot per robot, and an animated picture of the run; of a
fleet's run, the animated picture (:func:`animate` draws both kinds of world).
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any, BinaryIO

from robosc.sim.report import Report, robot_names
from robosc.sim.world import World

FRAME = "world"
POSE_SCHEMA = {
    "title": "foxglove.PoseInFrame",
    "type": "object",
    "properties": {"timestamp": {"type": "object"}, "frame_id": {"type": "string"}, "pose": {"type": "object"}},
}
SCAN_SCHEMA = {
    "title": "foxglove.LaserScan",
    "type": "object",
    "properties": {
        "timestamp": {"type": "object"},
        "frame_id": {"type": "string"},
        "pose": {"type": "object"},
        "start_angle": {"type": "number"},
        "end_angle": {"type": "number"},
        "ranges": {"type": "array", "items": {"type": "number"}},
        "intensities": {"type": "array", "items": {"type": "number"}},
    },
}
ANIMATION_FPS = 8
ANIMATION_STEP = 1.0  # seconds of simulated time per frame
RAYS = 36  # LiDAR rays drawn per robot


def write_recording(report: Report, world: World, folder: Path) -> list[Path]:
    """The MCAP file, the plots and the animation of a finished run; returns what it wrote."""
    from robosc.debug.eventlog import LogError, read_log

    folder.mkdir(parents=True, exist_ok=True)
    names = robot_names(len(report.robots))
    events: dict[str, list[Any]] = {}
    for name in names:
        path = folder / "events" / f"{name}.jsonl"
        try:
            events[name] = read_log(path) if path.exists() else []
        except LogError:
            events[name] = []
    written = []
    with open(folder / "run.mcap", "wb") as handle:
        write_mcap(report, world, events, handle)
    written.append(folder / "run.mcap")
    written += write_plots(events, folder)
    written.append(animate(report, world, folder / "run.gif"))
    return written


def _stamp(t: float) -> dict[str, int]:
    nanoseconds = round(t * 1e9)
    return {"sec": nanoseconds // 1_000_000_000, "nsec": nanoseconds % 1_000_000_000}


def _pose(x: float, y: float, heading: float) -> dict[str, Any]:
    return {
        "position": {"x": x, "y": y, "z": 0.0},
        "orientation": {"x": 0.0, "y": 0.0, "z": math.sin(heading / 2), "w": math.cos(heading / 2)},
    }


def pose_at(trajectory: list[tuple[float, float, float, float]], t: float) -> tuple[float, float, float]:
    """The last recorded pose at or before ``t``."""
    best = trajectory[0]
    for point in trajectory:
        if point[0] > t + 1e-9:
            break
        best = point
    return best[1], best[2], best[3]


def write_mcap(report: Report, world: World, events: dict[str, list[Any]], handle: BinaryIO) -> None:
    """Channels ``/robotK/pose``, ``/robotK/scan`` and ``/robotK/events``, by simulated time."""
    from mcap.writer import Writer

    from robosc.debug.eventlog import SCHEMA as EVENT_SCHEMA

    writer = Writer(handle)
    writer.start(profile="", library="robosc sim")
    schemas = {
        kind: writer.register_schema(schema["title"], "jsonschema", json.dumps(schema).encode())  # type: ignore[arg-type]
        for kind, schema in (("pose", POSE_SCHEMA), ("scan", SCAN_SCHEMA), ("events", EVENT_SCHEMA))
    }
    lidar = world.robot.lidar
    messages: list[tuple[float, int, dict[str, Any]]] = []
    for name, status in zip(robot_names(len(report.robots)), report.status, strict=True):
        channel = {kind: writer.register_channel(f"/{name}/{kind}", "json", schemas[kind]) for kind in schemas}
        for t, x, y, heading in status.trajectory:
            messages.append((t, channel["pose"], {"timestamp": _stamp(t), "frame_id": FRAME, "pose": _pose(x, y, heading)}))
        for t, ranges in status.scans:
            x, y, heading = pose_at(status.trajectory, t)
            scan = {
                "timestamp": _stamp(t),
                "frame_id": FRAME,
                "pose": _pose(x, y, heading),
                "start_angle": 0.0,
                "end_angle": 2 * math.pi * (lidar.beams - 1) / lidar.beams,
                "ranges": [r if math.isfinite(r) else 0.0 for r in ranges],  # 0: no return (JSON has no inf)
                "intensities": [],
            }
            messages.append((t, channel["scan"], scan))
        for record in events.get(name, []):
            messages.append((record.time, channel["events"], record.as_json()))
    messages.sort(key=lambda m: m[0])
    for sequence, (t, channel_id, data) in enumerate(messages):
        nanoseconds = max(0, round(t * 1e9))
        writer.add_message(
            channel_id,
            log_time=nanoseconds,
            publish_time=nanoseconds,
            sequence=sequence,
            data=json.dumps(data, sort_keys=True).encode(),
        )
    writer.finish()  # type: ignore[no-untyped-call]


def write_plots(events: dict[str, list[Any]], folder: Path) -> list[Path]:
    """The sequence-of-events plot of each robot that has events: ``robotK_events.png``."""
    from robosc.debug.plot import plot

    written = []
    for name, records in events.items():
        if records:
            written.append(plot(records, folder / f"{name}_events.png", title=f"{name}: {len(records):,} events"))
    return written


def animate(report: Report, world: World, output: Path) -> Path:
    """An animated GIF of a run (:func:`scene`), one frame per ``ANIMATION_STEP`` seconds of
    simulated time (``FLEET_STEP`` in a fleet's world)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.animation import FuncAnimation, PillowWriter

    fig, draw, frames = scene(report, world)
    animation = FuncAnimation(fig, draw, frames=frames, blit=False)
    animation.save(str(output), writer=PillowWriter(fps=ANIMATION_FPS))
    plt.close(fig)
    return output


def _figure(world: World, inches: float, dpi: int) -> tuple[Any, Any]:
    """A figure ``inches`` wide with the world's extent, to scale, without ticks."""
    import matplotlib.pyplot as plt

    width, height = world.size
    fig, ax = plt.subplots(figsize=(inches, inches * height / width + 0.4), dpi=dpi)
    ax.set_xlim(0, width)
    ax.set_ylim(0, height)
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    return fig, ax


ROBOT_COLOURS = ["#4e79a7", "#f28e2b", "#76b7b2", "#b07aa1", "#edc948", "#9c755f", "#ff9da7", "#bab0ac"]


FLEET_STEP = 2.0  # seconds of simulated time per frame of a fleet's animation
TRAIL = 10.0  # seconds of trajectory behind each robot of a fleet
CELL_COLOUR = "#dddddd"


def scene(report: Report, world: World) -> tuple[Any, Any, int]:
    """The animation's figure, its ``draw(frame)`` and the number of frames.

    Drawn: the goal, the track, the walls and boxes; in a fleet's world its cells (one with a
    single robot in it filled with that robot's colour), the door (red while not open) and the
    person. Each robot has a colour of its own and its name next to it; in a world with a goal
    its whole trajectory, its LiDAR rays and, where there are several, a legend (robots on the
    same spot, which do not see each other, have their names stacked, so that none hides
    another unseen); in a fleet's world its last ``TRAIL`` seconds of trajectory."""
    from matplotlib.patches import Circle, Polygon, Rectangle

    fleet = world.fleet
    height = world.size[1]
    fig, ax = _figure(world, 7.0, 72) if fleet is not None else _figure(world, 6.0, 80)
    cells = {}
    if fleet is not None:
        for name, polygon in fleet.cells:
            patch = Polygon(list(polygon), closed=True, facecolor=CELL_COLOUR, edgecolor="#999999", alpha=0.5)
            ax.add_patch(patch)
            cx = sum(q[0] for q in polygon) / len(polygon)
            ax.text(cx, max(q[1] for q in polygon) - 0.25, name, ha="center", fontsize=7, color="#777777")
            cells[name] = patch
    else:
        (gx0, gx1), (gy0, gy1) = world.goal.x, world.goal.y
        ax.add_patch(Rectangle((gx0, gy0), gx1 - gx0, gy1 - gy0, color="#59a14f", alpha=0.25))
        if world.line is not None:
            xs, ys = zip(*world.line.points, strict=True)
            ax.plot(xs, ys, color="#444444", linewidth=3, alpha=0.5)
    for wall in world.walls:
        ax.plot([q[0] for q in wall], [q[1] for q in wall], color="black", linewidth=2)
    if fleet is None:
        for x, y, w, h in world.boxes:
            ax.add_patch(Rectangle((x - w / 2, y - h / 2), w, h, color="#e15759"))
    door = None
    if fleet is not None and fleet.door is not None:
        (ax_, ay), (bx, by) = fleet.door.a, fleet.door.b
        (door,) = ax.plot([ax_, bx], [ay, by], color="#e15759", linewidth=4)
    radius = world.robot.radius
    paths, bodies, rays, names = [], [], [], []
    for k, robot in enumerate(report.robots):
        color = ROBOT_COLOURS[k % len(ROBOT_COLOURS)]
        (path,) = ax.plot([], [], color=color, linewidth=1, label=robot.name)
        size = radius if fleet is not None else radius * (1.0 - 0.15 * (k % 4))  # the later ones smaller, on top
        body = Circle((0, 0), size, color=color, zorder=3 if fleet is not None else 3 + k)
        ax.add_patch(body)
        if fleet is None:
            (ray,) = ax.plot([], [], color=color, linewidth=0.5, alpha=0.5)
            rays.append(ray)
        paths.append(path)
        bodies.append(body)
        names.append(ax.text(0, 0, robot.name, color=color, fontsize=7, fontweight="bold", zorder=10))
    if fleet is None and len(report.robots) > 1:
        ax.legend(loc="upper right", fontsize=7, framealpha=0.8)
    person = None
    if fleet is not None and report.person_trajectory:
        person = Circle((0, 0), fleet.person.radius if fleet.person else 0.25, color="#222222", zorder=4)
        ax.add_patch(person)
    title = ax.set_title("", fontsize=9, loc="left")
    end = report.simulated
    every = FLEET_STEP if fleet is not None else ANIMATION_STEP
    frames = max(1, int(end / every) + 1)
    lidar = world.robot.lidar
    step = 0.035 * height  # between stacked names
    colour_of = {k: ROBOT_COLOURS[k % len(ROBOT_COLOURS)] for k in range(len(report.robots))}

    def draw(frame: int) -> list[Any]:
        t = min(end, frame * every)
        placed: list[tuple[float, float]] = []
        inside: dict[str, list[int]] = {}
        for k, status in enumerate(report.status):
            since = t - TRAIL if fleet is not None else -math.inf
            shown = [q for q in status.trajectory if since <= q[0] <= t + 1e-9] or status.trajectory[:1]
            paths[k].set_data([q[1] for q in shown], [q[2] for q in shown])
            x, y, heading = shown[-1][1], shown[-1][2], shown[-1][3]
            bodies[k].center = (x, y)
            if fleet is not None:
                names[k].set_position((x + radius * 1.2, y + radius * 1.2))
                cell = fleet.cell(x, y)
                if cell:
                    inside.setdefault(cell, []).append(k)
                continue
            rays[k].set_data(*_rays(status.scans, t, x, y, heading, lidar.beams, lidar.range_max))
            near = sum(1 for px, py in placed if abs(px - x) < 2 * radius and abs(py - y) < 2 * radius)
            placed.append((x, y))
            names[k].set_position((x + radius * 1.2, y + radius * 1.2 + near * step))
        if fleet is None:
            title.set_text(f"t = {t:5.1f} s")
            return [*paths, *bodies, *rays, *names, title]
        for name, patch in cells.items():  # a cell with one robot in it has its colour
            robots = inside.get(name, [])
            patch.set_facecolor(colour_of[robots[0]] if len(robots) == 1 else CELL_COLOUR)
        if door is not None:
            state = [s for when, s in report.door_states if when <= t + 1e-9][-1:] or ["closed"]
            door.set_color("#59a14f" if state[0] == "open" else "#e15759")
        said = ""
        if person is not None:
            here = [q for q in report.person_trajectory if q[0] <= t + 1e-9] or list(report.person_trajectory[:1])
            person.center = (here[-1][1], here[-1][2])
            said = f", the person in {fleet.cell(here[-1][1], here[-1][2]) or 'no cell'}"
        title.set_text(f"t = {t:5.0f} s{said}")
        return [*paths, *bodies, *names, title]

    return fig, draw, frames


def _rays(
    scans: list[tuple[float, tuple[float, ...]]], t: float, x: float, y: float, heading: float, beams: int, range_max: float
) -> tuple[list[float], list[float]]:
    """Line segments (separated by NaN) from the robot along ``RAYS`` of its last scan."""
    kept = [s for s in scans if s[0] <= t + 1e-9]
    if not kept:
        return [], []
    ranges = kept[-1][1]
    xs: list[float] = []
    ys: list[float] = []
    for j in range(0, beams, max(1, beams // RAYS)):
        r = ranges[j] if math.isfinite(ranges[j]) else range_max
        angle = heading + 2 * math.pi * j / beams
        xs += [x, x + r * math.cos(angle), math.nan]
        ys += [y, y + r * math.sin(angle), math.nan]
    return xs, ys
