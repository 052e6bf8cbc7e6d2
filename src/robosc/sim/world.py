"""World files: what the 2D simulator builds (walls, boxes, a drawn line, the robots and their
sensors, the goal) and the topic names it uses, read from YAML and checked, with every problem
reported at its file, line and column.

The format is documented in ``examples/worlds/README.md``.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from robosc.record import field, record

# what the simulator publishes and subscribes, by role; the values are the default names
TOPIC_ROLES: dict[str, str] = {
    "scan": "/scan",  # sensor_msgs/LaserScan, published
    "cmd_vel": "/cmd_vel",  # geometry_msgs/Twist, subscribed
    "rotate_left": "/rotate_left",  # std_msgs/Int16 degrees, subscribed
    "rotate_right": "/rotate_right",  # std_msgs/Int16 degrees, subscribed
    "rotate_done": "/rotate_done",  # std_msgs/Empty, published when a rotation ends
    "line_correction": "/line/correction",  # std_msgs/Float32, published while the line is seen
    "line_lost": "/line/lost",  # std_msgs/Empty, published while it is not
    "stop": "/emergency_stop/stop",  # std_msgs/Empty, published when the button is pressed
    "continue": "/emergency_stop/continue",  # std_msgs/Empty, published when it is released
}


MAX_BYTES = 1_000_000  # a world file is a page of YAML; anything much bigger is a mistake
MAX_DEPTH = 32  # brackets in brackets (a wall is three deep)
MAX_LINE = 10_000  # characters


class WorldError(Exception):
    """A world file that cannot be used: the message names file, line and column."""

    def __init__(self, path: str, line: int, column: int, message: str) -> None:
        super().__init__(f"{path}:{line}:{column}: error: {message}")
        self.path, self.line, self.column, self.message = path, line, column, message


@record
class Pose:
    x: float
    y: float
    heading: float  # radians, counter-clockwise from the x axis


@record
class Lidar:
    beams: int = 360  # ranges[0] straight ahead, counter-clockwise (a TurtleBot's LDS)
    range_min: float = 0.12
    range_max: float = 3.5
    rate: float = 10.0  # scans per simulated second


@record
class Robot:
    radius: float = 0.1
    max_linear: float = 0.5  # m/s
    max_angular: float = 2.0  # rad/s
    turn_speed: float = 1.5  # rad/s while turning for a rotate command
    command_timeout: float = 0.5  # s a Twist is obeyed without a new one (as a real base)
    lidar: Lidar = field(default_factory=Lidar)


@record
class Line:
    """A line drawn on the floor and the detector that follows it."""

    points: tuple[tuple[float, float], ...]
    look_ahead: float = 0.15  # m in front of the robot's centre, where the detector looks
    width: float = 0.2  # m: the line is seen while it is this close to the look-ahead point
    gain: float = 300.0  # correction per metre the line lies to the right (negative: left)
    rate: float = 10.0  # readings per simulated second


@record
class Goal:
    """A rectangle every robot must reach; with ``stopped`` it must also stand still there
    for that many simulated seconds."""

    x: tuple[float, float]
    y: tuple[float, float]
    stopped: float = 0.0

    def contains(self, x: float, y: float) -> bool:
        return self.x[0] <= x <= self.x[1] and self.y[0] <= y <= self.y[1]


@record
class Door:
    """A door across a doorway (the segment ``a``-``b``): a robot may cross it only while it is
    open; opening and closing take ``seconds``."""

    a: tuple[float, float]
    b: tuple[float, float]
    seconds: float = 1.0


@record
class Charger:
    """Where a robot charges: it drives there from its home through ``home + via``, charges
    ``seconds``, drives back the same way and then says it is charged."""

    at: tuple[float, float]
    via: tuple[float, float] = (0.0, 0.0)
    seconds: float = 3.0


@record
class Person:
    """A person walking a scripted path: from the first point of ``walk`` to each next one at
    ``speed``, standing at a point for its seconds (a point's third number), after ``start``
    seconds; then the person stays at the last point. A person gives way: one who would come
    within ``GIVE_WAY`` metres of a robot waits where they are."""

    walk: tuple[tuple[float, float, float], ...]  # x, y, seconds standing there
    radius: float = 0.25
    speed: float = 0.6  # m/s
    start: float = 0.0  # s before the person sets off


@record
class Fleet:
    """What a fleet's robots do in the world. Each ``go`` of a robot drives the next leg of
    ``task`` (its waypoints in turn; ``home`` is the robot's start and ``lane`` its home +
    ``lane``), and the robot says ``arrived`` at the leg's end, or ``stopped`` where its way is
    blocked; ``cells`` name the places the report tells the robots in."""

    waypoints: tuple[tuple[str, tuple[float, float]], ...]
    task: tuple[tuple[str, ...], ...]  # every robot's task, unless ``tasks`` gives each its own
    cells: tuple[tuple[str, tuple[tuple[float, float], ...]], ...] = ()
    lane: tuple[float, float] = (0.0, 0.0)
    door: Door | None = None
    charger: Charger | None = None
    person: Person | None = None
    tasks: tuple[tuple[tuple[str, ...], ...], ...] = ()  # robot k's task: tasks[k - 1] (in turn)
    # one task in the model's terms, as the world gives it to the coordinator (--tasks K: K per
    # robot): the locations of a robot's automaton it must reach in turn; () gives none
    stops: tuple[str, ...] = ()

    def task_of(self, robot: int) -> tuple[tuple[str, ...], ...]:
        """The legs of robot ``robot``'s task (0 for the first robot)."""
        return self.tasks[robot % len(self.tasks)] if self.tasks else self.task

    def point(self, name: str, home: Pose) -> tuple[float, float]:
        """Where waypoint ``name`` is for the robot whose home is ``home``."""
        if name == "home":
            return home.x, home.y
        if name == "lane":
            return home.x + self.lane[0], home.y + self.lane[1]
        return dict(self.waypoints)[name]

    def cell(self, x: float, y: float) -> str:
        """The name of the cell (x, y) is in ("" for none)."""
        for name, polygon in self.cells:
            inside = False
            for (x1, y1), (x2, y2) in zip(polygon, polygon[1:] + polygon[:1], strict=True):
                if (y1 > y) != (y2 > y) and x < x1 + (y - y1) * (x2 - x1) / (y2 - y1):
                    inside = not inside
            if inside:
                return name
        return ""

    def cells_under(self, x: float, y: float, radius: float) -> frozenset[str]:
        """The cells a robot's body (a disc of ``radius`` round (x, y)) overlaps."""
        centre = self.cell(x, y)
        under = {centre} if centre else set()
        for name, polygon in self.cells:
            if any(to_segment(x, y, a, b) < radius for a, b in zip(polygon, polygon[1:] + polygon[:1], strict=True)):
                under.add(name)
        return frozenset(under)


def to_segment(x: float, y: float, a: tuple[float, float], b: tuple[float, float]) -> float:
    """The distance from (x, y) to the segment from ``a`` to ``b``."""
    dx, dy = b[0] - a[0], b[1] - a[1]
    length = dx * dx + dy * dy
    t = 0.0 if length == 0 else max(0.0, min(1.0, ((x - a[0]) * dx + (y - a[1]) * dy) / length))
    return math.hypot(x - (a[0] + t * dx), y - (a[1] + t * dy))


@record
class World:
    name: str
    path: str
    size: tuple[float, float]
    step: float  # simulated seconds per physics step
    robot: Robot
    starts: tuple[Pose, ...]
    goal: Goal
    walls: tuple[tuple[tuple[float, float], ...], ...]  # polylines
    boxes: tuple[tuple[float, float, float, float], ...]  # x, y (centre), width, height
    topics: dict[str, str] = field(compare=False)
    line: Line | None = None
    presses: tuple[tuple[float, float], ...] = ()  # emergency stop pressed over [t0, t1)
    # the robots are bodies to each other: one physics environment, each LiDAR sees the others,
    # and contact between robots is a collision; each robot needs a start of its own
    shared: bool = False
    fleet: Fleet | None = None  # a fleet's world: waypoints, the task, a door, a charger

    def start(self, index: int) -> Pose:
        """Robot ``index`` starts here (robots share the listed starts when there are more,
        in a world that is not ``shared``)."""
        return self.starts[index % len(self.starts)]

    def room_for(self, robots: int) -> str | None:
        """Why ``robots`` robots cannot run in this world, or None: a shared world needs a
        start for each."""
        if self.shared and robots > len(self.starts):
            return (
                f"{self.path}: the robots of this world are bodies to each other (shared: true), so each "
                f"needs a start of its own: it has {len(self.starts)}, and {robots} robots were asked for"
            )
        return None


# ---- reading -------------------------------------------------------------------------------


class _Reader:
    """Typed access to YAML nodes, raising WorldError at the node's position."""

    def __init__(self, path: str) -> None:
        self.path = path

    def fail(self, node: Any, message: str) -> WorldError:
        mark = node.start_mark
        return WorldError(self.path, mark.line + 1, mark.column + 1, message)

    def mapping(self, node: Any, what: str, allowed: set[str]) -> dict[str, Any]:
        import yaml

        if not isinstance(node, yaml.MappingNode):
            raise self.fail(node, f"{what} must be a mapping")
        out: dict[str, Any] = {}
        for key, value in node.value:
            name = key.value if isinstance(key, yaml.ScalarNode) else None
            if name not in allowed:
                import difflib

                close = difflib.get_close_matches(str(name), sorted(allowed), n=1)
                hint = f"; did you mean '{close[0]}'?" if close else f"; expected one of: {', '.join(sorted(allowed))}"
                raise self.fail(key, f"unknown key '{name}' in {what}{hint}")
            if name in out:
                raise self.fail(key, f"'{name}' given twice in {what}")
            out[name] = value
        return out

    def sequence(self, node: Any, what: str, length: int | None = None) -> list[Any]:
        import yaml

        if not isinstance(node, yaml.SequenceNode):
            raise self.fail(node, f"{what} must be a list")
        if length is not None and len(node.value) != length:
            raise self.fail(node, f"{what} must have {length} items, not {len(node.value)}")
        return list(node.value)

    def number(self, node: Any, what: str, low: float | None = None, positive: bool = False) -> float:
        import yaml

        if not isinstance(node, yaml.ScalarNode) or node.tag not in (
            "tag:yaml.org,2002:int",
            "tag:yaml.org,2002:float",
        ):
            raise self.fail(node, f"{what} must be a number")
        try:
            value = float(node.value.replace("_", ""))
        except ValueError:
            raise self.fail(node, f"{what} must be a number") from None
        if not math.isfinite(value):
            raise self.fail(node, f"{what} must be finite")
        if positive and value <= 0:
            raise self.fail(node, f"{what} must be greater than 0")
        if low is not None and value < low:
            raise self.fail(node, f"{what} must be at least {low:g}")
        return value

    def text(self, node: Any, what: str) -> str:
        import yaml

        if not isinstance(node, yaml.ScalarNode) or node.tag != "tag:yaml.org,2002:str" or not node.value:
            raise self.fail(node, f"{what} must be a non-empty text")
        return str(node.value)

    def flag(self, node: Any, what: str) -> bool:
        import yaml

        if not isinstance(node, yaml.ScalarNode) or node.tag != "tag:yaml.org,2002:bool":
            raise self.fail(node, f"{what} must be true or false")
        return node.value.lower() in ("true", "yes", "on")

    def point(self, node: Any, what: str) -> tuple[float, float]:
        x, y = self.sequence(node, what, 2)
        return self.number(x, what), self.number(y, what)

    def interval(self, node: Any, what: str) -> tuple[float, float]:
        low, high = self.sequence(node, what, 2)
        a, b = self.number(low, what), self.number(high, what)
        if a >= b:
            raise self.fail(node, f"{what} must be [low, high] with low < high")
        return a, b


def load_world(path: str | Path) -> World:
    """Read and check a world file; raises WorldError (file, line, column) on any problem."""
    import yaml

    name = str(path)
    text = _read(Path(path), name)
    _check_depth(text, name)
    loader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)  # libyaml where PyYAML has it
    try:
        for event in yaml.parse(text, Loader=loader):
            if isinstance(event, yaml.AliasEvent):  # a world is small: no need to share nodes
                mark = event.start_mark
                raise WorldError(name, mark.line + 1, mark.column + 1, "YAML aliases (*name) are not supported here")
        root = yaml.compose(text, Loader=loader)
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        line, column = (mark.line + 1, mark.column + 1) if mark else (1, 1)
        raise WorldError(name, line, column, f"not valid YAML: {exc.problem or exc.context}") from None
    except RecursionError:
        raise WorldError(name, 1, 1, "the world file is nested too deeply") from None
    if root is None:
        raise WorldError(name, 1, 1, "the world file is empty")
    return _world(_Reader(name), root)


def _read(path: Path, name: str) -> str:
    """The text of a regular file of at most ``MAX_BYTES``."""
    import stat

    try:
        info = path.stat()
        if not stat.S_ISREG(info.st_mode):
            raise WorldError(name, 1, 1, "not a regular file")
        if info.st_size > MAX_BYTES:
            raise WorldError(name, 1, 1, f"the world file has {info.st_size:,} bytes; at most {MAX_BYTES:,} are read")
        return path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise WorldError(name, 1, 1, f"cannot read the world file: {exc}") from None


def _check_depth(text: str, name: str) -> None:
    """Refuse brackets nested deeper than ``MAX_DEPTH`` (YAML parsers take time quadratic
    in the depth) and lines longer than ``MAX_LINE``, before parsing."""
    for number, text_line in enumerate(text.splitlines(), 1):
        if len(text_line) > MAX_LINE:
            raise WorldError(name, number, MAX_LINE + 1, f"line longer than {MAX_LINE:,} characters")
    depth = 0
    quote = ""
    line, column = 1, 0
    for char in text:
        column += 1
        if char == "\n":
            line, column = line + 1, 0
            quote = "" if quote == "#" else quote
        elif quote:
            if char == quote and quote != "#":
                quote = ""
        elif char in "\"'":
            quote = char
        elif char == "#":
            quote = "#"
        elif char in "[{":
            depth += 1
            if depth > MAX_DEPTH:
                raise WorldError(name, line, column, f"brackets nested more than {MAX_DEPTH} deep")
        elif char in "]}":
            depth = max(0, depth - 1)


def _world(r: _Reader, root: Any) -> World:
    keys = {
        "world", "size", "step", "robot", "starts", "goal", "walls", "boxes", "topics", "line", "emergency_stop",
        "shared", "fleet",
    }
    top = r.mapping(root, "the world", keys)
    for required in ("world", "size", "starts", "goal"):
        if required not in top:
            raise r.fail(root, f"the world needs '{required}'")
    width, height = (r.number(n, "size", positive=True) for n in r.sequence(top["size"], "size", 2))
    step = r.number(top["step"], "step", positive=True) if "step" in top else 0.05
    if step > 0.2:
        raise r.fail(top["step"], "step must be at most 0.2 s (the LiDAR and the turns need finer steps)")
    robot = _robot(r, top["robot"]) if "robot" in top else Robot()
    starts = []
    for node in r.sequence(top["starts"], "starts"):
        x, y, heading = (r.number(n, "a start") for n in r.sequence(node, "a start [x, y, heading]", 3))
        if not (0 <= x <= width and 0 <= y <= height):
            raise r.fail(node, "a start must lie inside the world")
        starts.append(Pose(x, y, math.radians(heading)))
    if not starts:
        raise r.fail(top["starts"], "the world needs at least one start")
    goal_keys = r.mapping(top["goal"], "goal", {"x", "y", "stopped"})
    for required in ("x", "y"):
        if required not in goal_keys:
            raise r.fail(top["goal"], f"the goal needs '{required}'")
    goal = Goal(
        r.interval(goal_keys["x"], "goal x"),
        r.interval(goal_keys["y"], "goal y"),
        r.number(goal_keys["stopped"], "goal stopped", low=0) if "stopped" in goal_keys else 0.0,
    )
    walls = []
    for node in r.sequence(top["walls"], "walls") if "walls" in top else []:
        points = tuple(r.point(p, "a wall point") for p in r.sequence(node, "a wall (a list of points)"))
        if len(points) < 2:
            raise r.fail(node, "a wall needs at least two points")
        walls.append(points)
    boxes = []
    for node in r.sequence(top["boxes"], "boxes") if "boxes" in top else []:
        x, y, w, h = (r.number(n, "a box") for n in r.sequence(node, "a box [x, y, width, height]", 4))
        if w <= 0 or h <= 0:
            raise r.fail(node, "a box needs a positive width and height")
        boxes.append((x, y, w, h))
    topics = dict(TOPIC_ROLES)
    if "topics" in top:
        for role, node in r.mapping(top["topics"], "topics", set(TOPIC_ROLES)).items():
            topics[role] = r.text(node, f"the topic of '{role}'")
    line = _line(r, top["line"]) if "line" in top else None
    shared = r.flag(top["shared"], "shared") if "shared" in top else False
    if shared:  # bodies to each other: no two may start touching
        nodes = r.sequence(top["starts"], "starts")
        for i, a in enumerate(starts):
            for j in range(i):
                b = starts[j]
                if math.hypot(a.x - b.x, a.y - b.y) <= 2 * robot.radius:
                    raise r.fail(nodes[i], f"start {i + 1} touches start {j + 1}: in a shared world robots are bodies")
    fleet = _fleet(r, top["fleet"]) if "fleet" in top else None
    if fleet is not None and not shared:
        raise r.fail(top["fleet"], "a fleet's world is shared: add 'shared: true' (its robots are bodies to each other)")
    presses = []
    if "emergency_stop" in top:
        for node in r.sequence(top["emergency_stop"], "emergency_stop (a list of [pressed, released] times)"):
            presses.append(r.interval(node, "an emergency stop press [pressed, released]"))
    return World(
        name=r.text(top["world"], "world"),
        path=r.path,
        size=(width, height),
        step=step,
        robot=robot,
        starts=tuple(starts),
        goal=goal,
        walls=tuple(walls),
        boxes=tuple(boxes),
        topics=topics,
        line=line,
        presses=tuple(presses),
        shared=shared,
        fleet=fleet,
    )


def _fleet(r: _Reader, node: Any) -> Fleet:
    top = r.mapping(
        node, "fleet", {"waypoints", "task", "tasks", "cells", "lane", "door", "charger", "person", "stops"}
    )
    if "waypoints" not in top:
        raise r.fail(node, "the fleet needs 'waypoints'")
    if ("task" in top) == ("tasks" in top):
        raise r.fail(node, "the fleet needs 'task' (every robot's) or 'tasks' (one per robot), not both")
    waypoints = {}
    for name, point in r.mapping(top["waypoints"], "waypoints", _AnyKey()).items():
        if name in ("home", "lane"):
            raise r.fail(point, f"'{name}' is each robot's own: it cannot be a waypoint")
        waypoints[name] = r.point(point, f"waypoint '{name}'")
    tasks: tuple[tuple[tuple[str, ...], ...], ...] = ()
    if "tasks" in top:
        tasks = tuple(_task(r, t, waypoints) for t in r.sequence(top["tasks"], "tasks (one task per robot)"))
        if not tasks:
            raise r.fail(top["tasks"], "'tasks' needs at least one task")
    task = tasks[0] if tasks else _task(r, top["task"], waypoints)
    cells = []
    for name, polygon in (r.mapping(top["cells"], "cells", _AnyKey()).items() if "cells" in top else []):
        points = tuple(r.point(p, f"a corner of cell '{name}'") for p in r.sequence(polygon, f"cell '{name}'"))
        if len(points) < 3:
            raise r.fail(polygon, f"cell '{name}' needs at least three corners")
        cells.append((name, points))
    lane = r.point(top["lane"], "lane") if "lane" in top else (0.0, 0.0)
    door = None
    if "door" in top:
        d = r.mapping(top["door"], "door", {"from", "to", "seconds"})
        for required in ("from", "to"):
            if required not in d:
                raise r.fail(top["door"], f"the door needs '{required}'")
        seconds = r.number(d["seconds"], "door seconds", positive=True) if "seconds" in d else 1.0
        door = Door(r.point(d["from"], "door from"), r.point(d["to"], "door to"), seconds)
    charger = None
    if "charger" in top:
        c = r.mapping(top["charger"], "charger", {"at", "via", "seconds"})
        if "at" not in c:
            raise r.fail(top["charger"], "the charger needs 'at'")
        charger = Charger(
            r.point(c["at"], "charger at"),
            r.point(c["via"], "charger via") if "via" in c else (0.0, 0.0),
            r.number(c["seconds"], "charger seconds", positive=True) if "seconds" in c else 3.0,
        )
    person = _person(r, top["person"]) if "person" in top else None
    stops: tuple[str, ...] = ()
    if "stops" in top:
        stops = tuple(r.text(s, "a stop (a location of the robot's automaton)") for s in r.sequence(top["stops"], "stops"))
        if not stops:
            raise r.fail(top["stops"], "'stops' needs at least one location")
    return Fleet(tuple(waypoints.items()), task, tuple(cells), lane, door, charger, person, tasks, stops)


def _task(r: _Reader, node: Any, waypoints: dict[str, tuple[float, float]]) -> tuple[tuple[str, ...], ...]:
    import yaml

    task = []
    for leg in r.sequence(node, "task (one list of waypoints per go)"):
        names = r.sequence(leg, "a leg of the task (a list of waypoints)")
        if not names:
            raise r.fail(leg, "a leg of the task needs at least one waypoint")
        for n in names:
            if not isinstance(n, yaml.ScalarNode) or (n.value not in waypoints and n.value not in ("home", "lane")):
                raise r.fail(n, f"unknown waypoint '{getattr(n, 'value', n)}' (the waypoints, home, lane)")
        task.append(tuple(str(n.value) for n in names))
    if not task:
        raise r.fail(node, "the task needs at least one leg")
    return tuple(task)


def _person(r: _Reader, node: Any) -> Person:
    keys = r.mapping(node, "person", {"walk", "radius", "speed", "start"})
    if "walk" not in keys:
        raise r.fail(node, "the person needs 'walk' (the points they walk to in turn)")
    walk = []
    for point in r.sequence(keys["walk"], "walk (a list of [x, y] or [x, y, seconds standing there])"):
        items = r.sequence(point, "a point of the walk ([x, y] or [x, y, seconds standing there])")
        if len(items) not in (2, 3):
            raise r.fail(point, "a point of the walk is [x, y] or [x, y, seconds standing there]")
        stand = r.number(items[2], "seconds standing there", low=0) if len(items) == 3 else 0.0
        walk.append((r.number(items[0], "x"), r.number(items[1], "y"), stand))
    if not walk:
        raise r.fail(keys["walk"], "the walk needs at least one point")
    return Person(
        tuple(walk),
        r.number(keys["radius"], "person radius", positive=True) if "radius" in keys else 0.25,
        r.number(keys["speed"], "person speed", positive=True) if "speed" in keys else 0.6,
        r.number(keys["start"], "person start", low=0) if "start" in keys else 0.0,
    )


class _AnyKey(set):  # type: ignore[type-arg]
    """Every key is allowed (named waypoints and cells)."""

    def __contains__(self, item: object) -> bool:
        return isinstance(item, str) and bool(item)


def _robot(r: _Reader, node: Any) -> Robot:
    keys = r.mapping(node, "robot", {"radius", "max_linear", "max_angular", "turn_speed", "command_timeout", "lidar"})
    values = {k: r.number(v, k, positive=True) for k, v in keys.items() if k != "lidar"}
    lidar = Lidar()
    if "lidar" in keys:
        lidar_keys = r.mapping(keys["lidar"], "lidar", {"beams", "range_min", "range_max", "rate"})
        numbers = {k: r.number(v, k, low=0) for k, v in lidar_keys.items()}
        beams = numbers.pop("beams", 360)
        if beams != int(beams) or not 4 <= beams <= 4096:
            raise r.fail(lidar_keys["beams"], "beams must be a whole number from 4 to 4096")
        lidar = Lidar(beams=int(beams), **numbers)
        if lidar.range_max <= lidar.range_min or lidar.rate <= 0:
            raise r.fail(keys["lidar"], "the lidar needs range_min < range_max and a rate above 0")
    return Robot(lidar=lidar, **values)


def _line(r: _Reader, node: Any) -> Line:
    keys = r.mapping(node, "line", {"points", "look_ahead", "width", "gain", "rate"})
    if "points" not in keys:
        raise r.fail(node, "the line needs 'points'")
    points = tuple(r.point(p, "a line point") for p in r.sequence(keys["points"], "line points"))
    if len(points) < 2:
        raise r.fail(keys["points"], "the line needs at least two points")
    values = {k: r.number(v, k, positive=k != "gain") for k, v in keys.items() if k != "points"}
    return Line(points=points, **values)
