"""Scaling families of RoboSC models for the synthesis benchmark (and its tests)."""

from __future__ import annotations

from pathlib import Path


def transfer_line(n: int) -> str:
    """N machines in a row with a one-slot buffer between each pair (Ramadge-Wonham's
    small factory, stretched). A part made into a full buffer overflows it, and an
    overflow blocks: synthesis must keep each machine from starting while its
    output buffer is full."""
    lines = ["robot TransferLine {", "    interface trigger use Trigger from std_srvs"]
    for i in range(1, n + 1):
        lines.append(f"    component M{i} {{ service work{i} with request: none, response: none links trigger }}")
    for i in range(1, n):
        lines.append(f"""    component B{i} {{
        behaviour {{
            initial marked state empty {{ on response from work{i} goto full }}
            marked state full {{
                on request to work{i + 1} goto empty
                on response from work{i} goto overflow
            }}
            state overflow {{ on request to clear{i} goto empty }}
        }}
    }}
    component Operator{i} {{ service clear{i} with request: none, response: none links trigger }}
    requirement clear{i} needs B{i}.empty""")
    lines.append("}")
    return "\n".join(lines) + "\n"


def enum_sensors(n: int) -> str:
    """N components, each with a sensor turned into an enum and a command that needs it."""
    lines = ["robot EnumSensors {"]
    for i in range(n):
        lines.append(f"""    datatype enum Level{i} from double to {{
        value < 0.5 -> low{i}
        default -> high{i}
    }}
    component Part{i} {{
        outgoing message sense{i} with type: Level{i}
        incoming message act{i} with type: none
        behaviour {{
            variable level: Level{i} = low{i}
            on response from sense{i} do level := value
            initial marked state idle {{ on request to act{i} }}
        }}
    }}
    requirement act{i} needs Part{i}.level = high{i}""")
    lines.append("}")
    return "\n".join(lines) + "\n"


def philosophers(n: int) -> str:
    """N dining philosophers and N forks. A philosopher takes the left fork, then starts
    eating (a service call) by taking the right one; when the call returns both forks
    are free again. Everyone holding a left fork is a deadlock: synthesis must prevent it."""
    lines = ["robot Philosophers {", "    interface trigger use Trigger from std_srvs"]
    for i in range(n):
        before = (i - 1) % n  # fork i is the left fork of P{i} and the right fork of P{before}
        lines.append(f"""    component P{i} {{
        incoming message take_left{i} with type: none
        service eat{i} with request: none, response: none links trigger
        behaviour {{
            initial marked state thinking {{ on request to take_left{i} goto has_left }}
            state has_left {{ on request to eat{i} goto eating }}
            state eating {{
                on response from eat{i} goto thinking
                on error from eat{i} goto thinking
            }}
        }}
    }}
    component F{i} {{
        behaviour {{
            initial marked state free {{
                on request to take_left{i} goto taken
                on request to eat{before} goto taken
            }}
            state taken {{
                on response from eat{i} goto free
                on error from eat{i} goto free
                on response from eat{before} goto free
                on error from eat{before} goto free
            }}
        }}
    }}""")
    lines.append("}")
    return "\n".join(lines) + "\n"


FAMILIES = {
    "transfer line (N machines, N-1 buffers)": transfer_line,
    "enum sensors (N components)": enum_sensors,
    "dining philosophers (N)": philosophers,
}


def _next_zone_free(i: int, n: int, zones: int, also: dict[int, str] | None = None) -> str:
    """Robot i's requirement for a move, in the copied form: wherever it is, no other robot holds
    the next zone (is in it, or moving into or out of it); ``also``: more to hold before a move
    into a zone (its index -> a condition)."""
    parts = []
    for k in range(zones):
        nxt = (k + 1) % zones
        held = " or ".join(f"R{j}.at{nxt} or R{j}.moving{k} or R{j}.moving{nxt}" for j in range(n) if j != i)
        free = f"!({held})" if held else "true"
        if also and nxt in also:  # in parentheses: `=>` binds tighter than `and`
            free = f"({free} and {also[nxt]})"
        parts.append(f"(R{i}.at{k} => {free})")
    return " and ".join(parts)


SPLIT_FROM = 16  # more robots: one requirement per robot and zone (one per robot nests too deep to read)


def ring(n: int, homes: bool = False) -> str:
    """N robots on a one-way ring of 2N zones, written as today's language allows (a copied
    component per robot): robot i starts in zone 2i; `go{i}` (the controller's) starts a move
    into the next zone, `arrived{i}` (the robot's) ends it. A zone is held by the robot in it
    and by the one moving into it or out of it; a robot may start a move only into a zone no
    other robot holds: a requirement per robot naming every other robot for every zone (beyond
    :data:`SPLIT_FROM` robots, one per robot and zone: a requirement per robot would be an
    expression more than 100 levels deep, which the language refuses). With ``homes``, a robot
    rests only in its start zone (its only marked state): see ring_homes."""
    starts = [2 * i for i in range(n)]
    return ring_of(2 * n, starts, starts if homes else None)


def ring_of(zones: int, starts: list[int], homes: list[int] | None = None) -> str:
    """:func:`ring`'s robots on a one-way ring of ``zones`` zones, robot i starting in zone
    ``starts[i]``; with ``homes``, resting only in zone ``homes[i]`` (else in every zone)."""
    n = len(starts)
    lines = ["robot Homes {" if homes is not None else "robot Ring {"]
    for i in range(n):
        states = []
        for k in range(zones):
            initial = "initial " if k == starts[i] else ""
            marked = "marked " if homes is None or k == homes[i] else ""
            states.append(f"            {initial}{marked}state at{k} {{ on request to go{i} goto moving{k} }}")
            states.append(f"            state moving{k} {{ on response from arrived{i} goto at{(k + 1) % zones} }}")
        lines.append(
            f"    component R{i} {{\n"
            f"        incoming message go{i} with type: none\n"
            f"        outgoing message arrived{i} with type: none\n"
            "        behaviour {\n" + "\n".join(states) + "\n        }\n    }"
        )
    for i in range(n):
        if n <= SPLIT_FROM:
            lines.append(f"    requirement go{i} needs {_next_zone_free(i, n, zones)}")
            continue
        for k in range(zones):  # (the same, written as the language's depth limit asks)
            nxt = (k + 1) % zones
            free = " and ".join(f"!(R{j}.at{nxt} or R{j}.moving{k} or R{j}.moving{nxt})" for j in range(n) if j != i)
            lines.append(f"    requirement go{i} needs R{i}.at{k} => ({free})")
    lines.append("}")
    return "\n".join(lines) + "\n"


def warehouse(n: int) -> str:
    """N robots in a warehouse, written as today's language allows (a copied component per
    robot): a one-way loop of 2N+2 aisle zones, each taking one robot at a time; zone 1 is a
    door the robots pass only while it is open (the door opens and closes on command and says
    when it is done, and may close only while no robot is in it); one charger off zone 0, for
    one robot at a time, which says when the robot is charged. A robot rests (marked) only in
    an aisle zone, not in the door or while charging."""
    zones = 2 * n + 2
    door = 1
    lines = ["robot Warehouse {"]
    lines.append(
        "    component Door {\n"
        "        incoming message open_door with type: none\n"
        "        incoming message close_door with type: none\n"
        "        outgoing message door_opened with type: none\n"
        "        outgoing message door_closed with type: none\n"
        "        behaviour {\n"
        "            initial marked state closed { on request to open_door goto opening }\n"
        "            state opening { on response from door_opened goto open }\n"
        "            marked state open { on request to close_door goto closing }\n"
        "            state closing { on response from door_closed goto closed }\n"
        "        }\n    }"
    )
    for i in range(n):
        states = []
        for k in range(zones):
            initial = "initial " if k == 2 * i + 2 else ""
            marked = "" if k == door else "marked "
            charge = f" on request to dock{i} goto charging" if k == 0 else ""
            states.append(f"            {initial}{marked}state at{k} {{ on request to go{i} goto moving{k}{charge} }}")
            states.append(f"            state moving{k} {{ on response from arrived{i} goto at{(k + 1) % zones} }}")
        states.append(f"            state charging {{ on response from charged{i} goto at0 }}")
        lines.append(
            f"    component R{i} {{\n"
            f"        incoming message go{i} with type: none\n"
            f"        incoming message dock{i} with type: none\n"
            f"        outgoing message arrived{i} with type: none\n"
            f"        outgoing message charged{i} with type: none\n"
            "        behaviour {\n" + "\n".join(states) + "\n        }\n    }"
        )
    for i in range(n):
        lines.append(f"    requirement go{i} needs {_next_zone_free(i, n, zones, {door: 'Door.open'})}")
        others = " or ".join(f"R{j}.charging" for j in range(n) if j != i)
        lines.append(f"    requirement dock{i} needs " + (f"!({others})" if others else "true"))
    in_door = " or ".join(f"R{j}.at{door} or R{j}.moving{door - 1} or R{j}.moving{door}" for j in range(n))
    lines.append(f"    requirement close_door needs !({in_door})")
    lines.append("}")
    return "\n".join(lines) + "\n"


def ring_counted(n: int) -> str:
    """The ring with the robots' identities abstracted away by hand (a counter abstraction,
    what synthesis for identical instances could do by itself): a component per zone, empty,
    a robot in it, or a robot moving out of it; a move needs the next zone empty. Measured to
    see whether symmetry pays before building it into synthesis."""
    z = 2 * n
    lines = ["robot RingCounted {"]
    for k in range(z):
        start = "at" if k % 2 == 0 else "empty"

        def state(name: str, body: str, marked: bool = True, start: str = start) -> str:
            return f"            {'initial ' if name == start else ''}{'marked ' if marked else ''}state {name} {{ {body} }}"

        lines.append(
            f"    component Z{k} {{\n        incoming message go{k} with type: none\n"
            f"        outgoing message arrived{k} with type: none\n        behaviour {{"
        )
        lines.append(state("empty", f"on response from arrived{(k - 1) % z} goto at"))
        lines.append(state("at", f"on request to go{k} goto moving"))
        lines.append(state("moving", f"on response from arrived{k} goto empty", marked=False))
        lines.append("        }\n    }")
    for k in range(z):
        lines.append(f"    requirement go{k} needs Z{(k + 1) % z}.empty")
    lines.append("}")
    return "\n".join(lines) + "\n"


def _zone_free(zones: int, also: dict[int, str] | None = None) -> str:
    """The move requirement of instance ``r``, written once: wherever r is, no robot holds the
    next zone (r itself cannot: it is in the zone before)."""
    parts = []
    for k in range(zones):
        nxt = (k + 1) % zones
        free = f"!any(q in bot: q.at{nxt} or q.moving{k} or q.moving{nxt})"
        if also and nxt in also:  # in parentheses: `=>` binds tighter than `and`
            free = f"({free} and {also[nxt]})"
        parts.append(f"(r.at{k} => {free})")
    return " and ".join(parts)


def _robot_states(zones: int, door: int | None = None, charger: bool = False) -> list[str]:
    states = []
    for k in range(zones):
        marked = "" if k == door else "marked "
        dock = " on request to dock goto charging" if charger and k == 0 else ""
        states.append(f"            {marked}state at{k} {{ on request to go goto moving{k}{dock} }}")
        states.append(f"            state moving{k} {{ on response from arrived goto at{(k + 1) % zones} }}")
    if charger:
        states.append("            state charging { on response from charged goto at0 }")
    return states


def ring_instances(n: int) -> str:
    """:func:`ring` written with instances: one robot component for all, bot1 .. botN (bot{i+1}
    is R{i} and starts in zone 2i), and the move requirement written once for every robot."""
    zones = 2 * n
    starts = ", ".join(f"at{2 * i}" for i in range(n))
    return "\n".join(
        [
            "robot Ring {",
            f"    component bot[{n}] initial {starts} {{",
            "        incoming message go with type: none",
            "        outgoing message arrived with type: none",
            "        behaviour {",
            *_robot_states(zones),
            "        }",
            "    }",
            "    for r in bot {",
            f"        requirement r.go needs {_zone_free(zones)}",
            "    }",
            "}",
        ]
    ) + "\n"


def warehouse_instances(n: int) -> str:
    """:func:`warehouse` written with instances (bot{i+1} is R{i})."""
    zones = 2 * n + 2
    door = 1
    starts = ", ".join(f"at{2 * i + 2}" for i in range(n))
    return "\n".join(
        [
            "robot Warehouse {",
            "    component Door {",
            "        incoming message open_door with type: none",
            "        incoming message close_door with type: none",
            "        outgoing message door_opened with type: none",
            "        outgoing message door_closed with type: none",
            "        behaviour {",
            "            initial marked state closed { on request to open_door goto opening }",
            "            state opening { on response from door_opened goto open }",
            "            marked state open { on request to close_door goto closing }",
            "            state closing { on response from door_closed goto closed }",
            "        }",
            "    }",
            f"    component bot[{n}] initial {starts} {{",
            "        incoming message go with type: none",
            "        incoming message dock with type: none",
            "        outgoing message arrived with type: none",
            "        outgoing message charged with type: none",
            "        behaviour {",
            *_robot_states(zones, door, charger=True),
            "        }",
            "    }",
            "    for r in bot {",
            f"        requirement r.go needs {_zone_free(zones, {door: 'Door.open'})}",
            "        requirement r.dock needs !any(q in bot: q.charging)",
            "    }",
            f"    requirement close_door needs !any(q in bot: q.at{door} or q.moving{door - 1} or q.moving{door})",
            "}",
        ]
    ) + "\n"


def lift(n: int) -> str:
    """N robots (instances) share a corridor cell and a lift of capacity 2 to the floor above,
    where they work, then ride down and go home: each robot in 13 states, one shared lift
    automaton, thresholds of 1 (the corridor, a robot at a time) and 2 (the lift's riders)."""
    riders = "count(q in bot: q.riding_up or q.riding_down)"
    corridor_free = "!any(q in bot: q.corridor or q.waiting or q.returning)"
    return "\n".join(
        [
            "robot LiftFleet {",
            "    component Lift {",
            "        incoming message up with type: none",
            "        incoming message down with type: none",
            "        outgoing message at_top with type: none",
            "        outgoing message at_ground with type: none",
            "        behaviour {",
            "            initial marked state ground { on request to up goto rising }",
            "            state rising { on response from at_top goto top }",
            "            marked state top { on request to down goto sinking }",
            "            state sinking { on response from at_ground goto ground }",
            "        }",
            "    }",
            f"    component bot[{n}] {{",
            *(
                f"        incoming message {name} with type: none"
                for name in ("go", "call", "board", "alight", "work", "call_down", "board_down", "alight_down", "home")
            ),
            "        outgoing message done with type: none",
            "        behaviour {",
            "            initial marked state depot { on request to go goto corridor }",
            "            state corridor { on request to call goto waiting }",
            "            state waiting { on request to board goto riding_up }",
            "            state riding_up { on request to alight goto upstairs }",
            "            state upstairs { on request to work goto working }",
            "            state working { on response from done goto finished }",
            "            state finished { on request to call_down goto waiting_down }",
            "            state waiting_down { on request to board_down goto riding_down }",
            "            state riding_down { on request to alight_down goto returning }",
            "            state returning { on request to home goto depot }",
            "        }",
            "    }",
            "    for r in bot {",
            f"        requirement r.go needs {corridor_free}",
            f"        requirement r.board needs Lift.ground and {riders} < 2",
            "        requirement r.alight needs Lift.top",
            f"        requirement r.board_down needs Lift.top and {riders} < 2",
            f"        requirement r.alight_down needs Lift.ground and {corridor_free}",
            "    }",
            f"    requirement up needs {riders} >= 1",
            f"    requirement down needs {riders} >= 1",
            "}",
        ]
    ) + "\n"


def ring_homes(n: int) -> str:
    """:func:`ring`, but each robot must be able to get back to a home of its own, its start
    zone (the only marked state of its component): copies by hand that differ in one place."""
    return ring(n, homes=True)


def crossing(n: int) -> str:
    """Two kinds of robots whose routes cross: N/2 eastbound (instances east) on a one-way loop
    of 2N cells, N - N/2 southbound (south) on another; the loops share two crossing cells
    (east's cells 1 and N+1 are south's cells 1 and N+1), each for one robot of either kind."""
    zones = 2 * n
    kinds = {"east": n // 2, "south": n - n // 2}
    crossings = (1, n + 1)
    lines = ["robot Crossing {"]
    for kind, count in kinds.items():
        starts = ", ".join(f"at{2 * i + 2}" for i in range(count))
        lines += [
            f"    component {kind}[{count}] initial {starts} {{",
            "        incoming message go with type: none",
            "        outgoing message arrived with type: none",
            "        behaviour {",
            *_robot_states(zones),
            "        }",
            "    }",
        ]
    for kind, other in (("east", "south"), ("south", "east")):
        parts = []
        for k in range(zones):
            nxt = (k + 1) % zones
            free = f"!any(q in {kind}: q.at{nxt} or q.moving{k} or q.moving{nxt})"
            if nxt in crossings:
                free += f" and !any(q in {other}: q.at{nxt} or q.moving{nxt - 1} or q.moving{nxt})"
            parts.append(f"(r.at{k} => ({free}))")
        lines += [f"    for r in {kind} {{", f"        requirement r.go needs {' and '.join(parts)}", "    }"]
    lines.append("}")
    return "\n".join(lines) + "\n"


def warehouse_example(n: int) -> str:
    """The bundled ``examples/warehouse.rscd`` with N robots (``component bot[N]``): moves that
    take time and may stop, a door, one charger a robot uses at most once between tasks, the
    person's cell (26 states per robot)."""
    text = (Path(__file__).resolve().parent.parent / "examples" / "warehouse.rscd").read_text()
    sized = text.replace("component bot[3]", f"component bot[{n}]", 1)
    if sized == text:
        raise ValueError("examples/warehouse.rscd no longer declares component bot[3]")
    return sized


FLEETS = {
    "ring": ring,
    "warehouse": warehouse,
    "ring_counted": ring_counted,
    "ring_instances": ring_instances,
    "warehouse_instances": warehouse_instances,
    "lift": lift,
    "ring_homes": ring_homes,
    "crossing": crossing,
    "warehouse_example": warehouse_example,
}  # fleet families (benchmarks/fleet_synthesis.py): N robots
