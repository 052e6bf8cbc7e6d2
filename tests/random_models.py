"""A hypothesis strategy for small random RoboSC robots (valid by construction), used to
cross-check the synthesis methods against each other and against libFAUDES."""

from __future__ import annotations

from hypothesis import strategies as st


@st.composite
def robots(draw: st.DrawFn, variables: bool = True, guards: bool = True) -> str:
    """A robot text. With ``variables=False, guards=False`` it has plain automata and
    requirements over one component's states only (what libFAUDES can take)."""
    n_components = draw(st.integers(1, 3))
    lines = ["robot Random {"]
    components = []
    for c in range(n_components):
        states = [f"s{c}_{i}" for i in range(draw(st.integers(1, 3)))]
        sensors = [f"sense{c}_{i}" for i in range(draw(st.integers(1, 2)))]
        commands = [f"cmd{c}_{i}" for i in range(draw(st.integers(0, 2)))]
        service = draw(st.booleans())
        components.append((c, states, sensors, commands, service))
        lines.append(f"  component C{c} {{")
        lines += [f"    outgoing message {s} with type: none" for s in sensors]
        lines += [f"    incoming message {k} with type: none" for k in commands]
        if service:
            lines.append(f"    service srv{c} with request: none, response: none")
        lines.append("    behaviour {")
        if variables:
            lines.append(f"      variable flag: boolean = {draw(st.sampled_from(['true', 'false']))}")
            lines.append(f"      variable n: integer(0..2) = {draw(st.integers(0, 2))}")
        events = [("response from", s) for s in sensors] + [("request to", k) for k in commands]
        if service:
            events += [("request to", f"srv{c}"), ("response from", f"srv{c}"), ("error from", f"srv{c}")]
        marked = draw(st.lists(st.sampled_from(states), min_size=1, unique=True))
        for i, state in enumerate(states):
            flags = ("initial " if i == 0 else "") + ("marked " if state in marked else "")
            lines.append(f"      {flags}state {state} {{")
            for _ in range(draw(st.integers(0, 3))):
                kind, name = draw(st.sampled_from(events))
                target = draw(st.sampled_from([None, *states]))
                assignment = ""
                if variables and kind == "response from" and draw(st.booleans()):
                    assignment = draw(st.sampled_from([" do n := n + 1", " do n := 0", " do flag := !flag"]))
                goto = f" goto {target}" if target else ""
                lines.append(f"        on {kind} {name}{assignment}{goto}")
            # a way back to the initial state keeps every state able to reach a marked one (rule 3)
            guard = ""
            if guards and draw(st.booleans()):
                guard = " if " + draw(st.sampled_from(["flag", "n < 2", "!flag or n = 0"] if variables else ["true"]))
            if state not in marked or draw(st.booleans()):
                lines.append(f"        transition{guard} goto {states[0] if states[0] in marked else marked[0]}")
            lines.append("      }")
        lines.append("    }")
        lines.append("  }")
    # requirements
    triggers = [k for _, _, _, ks, _ in components for k in ks]
    triggers += [f"srv{c}" for c, _, _, _, srv in components if srv]
    sensors_all = [s for _, _, ss, _, _ in components for s in ss]
    for _ in range(draw(st.integers(0, 3))):
        c, states, _, _, _ = draw(st.sampled_from(components))
        picked = draw(st.lists(st.sampled_from(states), min_size=1, max_size=2, unique=True))
        condition = " or ".join(f"C{c}.{s}" for s in picked)
        if variables and draw(st.booleans()):
            condition = f"({condition}) and C{c}.n {draw(st.sampled_from(['<', '=', '>=']))} 1"
        pool = triggers + (sensors_all if draw(st.integers(0, 3)) == 0 else [])
        if not pool:
            continue
        event = draw(st.sampled_from(pool))
        if draw(st.booleans()):
            lines.append(f"  requirement {event} needs {condition}")
        else:
            lines.append(f"  requirement {condition} disables {event}")
    lines.append("}")
    return "\n".join(lines) + "\n"
