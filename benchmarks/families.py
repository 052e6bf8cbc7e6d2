"""Scaling families of RoboSC models for the synthesis benchmark (and its tests)."""

from __future__ import annotations


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
