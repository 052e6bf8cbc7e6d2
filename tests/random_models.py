"""A hypothesis strategy for small random RoboSC robots (valid by construction), used to
cross-check the synthesis methods against each other and against libFAUDES."""

from __future__ import annotations

from hypothesis import strategies as st

from robosc.language.keywords import KEYWORDS

# Names that meet each other or the generated code's own names once joined with '_' or
# put in Python: keywords (escaped with '^' where RoboSC reserves them), names of the
# runtime and of the generated module, and pairs like A.b_c / A_b.c, s.u_response / s_u_response.
COMPONENT_NAMES = ["A", "A_b", "class", "Robot", "timer", "_", "rt", "self"]
VARIABLE_NAMES = [("b_c", "c"), ("lock", "tick"), ("None", "value"), ("state", "data"), ("send", "out")]
MESSAGE_NAMES = ["timer", "tick", "s_u_response", "lock", "send", "to", "Comm", "REFUSED", "lambda", "Event"]
STATE_NAMES = ["ready", "self", "None", "state", "a_b", "a", "b"]


def escaped(name: str) -> str:
    return f"^{name}" if name in KEYWORDS else name


@st.composite
def robots(draw: st.DrawFn, variables: bool = True, guards: bool = True, adversarial: bool = False) -> str:
    """A robot text. With ``variables=False, guards=False`` it has plain automata and
    requirements over one component's states only (what libFAUDES can take). With
    ``adversarial``, its names are chosen to collide once turned into code."""
    n_components = draw(st.integers(1, 3))
    lines = ["robot Random {", "  interface trigger use Trigger from std_srvs"]
    components = []
    component_names = draw(st.permutations(COMPONENT_NAMES))[:n_components] if adversarial else []
    message_pool = list(draw(st.permutations(MESSAGE_NAMES))) if adversarial else []
    for c in range(n_components):
        states = [f"s{c}_{i}" for i in range(draw(st.integers(1, 3)))]
        sensors = [f"sense{c}_{i}" for i in range(draw(st.integers(1, 2)))]
        commands = [f"cmd{c}_{i}" for i in range(draw(st.integers(0, 2)))]
        if adversarial:
            states = [escaped(s) for s in draw(st.permutations(STATE_NAMES))[: len(states)]]
            sensors = [escaped(message_pool.pop()) if message_pool else s for s in sensors]
            commands = [escaped(message_pool.pop()) if message_pool else k for k in commands]
        service = draw(st.booleans())
        name = escaped(component_names[c]) if adversarial else f"C{c}"
        flag, n = draw(st.sampled_from(VARIABLE_NAMES)) if adversarial else ("flag", "n")
        flag, n = escaped(flag), escaped(n)
        srv = f"s{c}" if not adversarial or c else "s"  # "s": its response event s.u_response meets s_u_response
        srv = srv if adversarial else f"srv{c}"
        components.append((name, states, sensors, commands, service, srv, flag, n))
        lines.append(f"  component {name} {{")
        lines += [f"    outgoing message {s} with type: none" for s in sensors]
        lines += [f"    incoming message {k} with type: none" for k in commands]
        if service:
            lines.append(f"    service {srv} with request: none, response: none links trigger")
        lines.append("    behaviour {")
        if variables:
            lines.append(f"      variable {flag}: boolean = {draw(st.sampled_from(['true', 'false']))}")
            lines.append(f"      variable {n}: integer(0..2) = {draw(st.integers(0, 2))}")
        events = [("response from", s) for s in sensors] + [("request to", k) for k in commands]
        if service:
            events += [("request to", srv), ("response from", srv), ("error from", srv)]
        marked = draw(st.lists(st.sampled_from(states), min_size=1, unique=True))
        for i, state in enumerate(states):
            flags = ("initial " if i == 0 else "") + ("marked " if state in marked else "")
            lines.append(f"      {flags}state {state} {{")
            for _ in range(draw(st.integers(0, 3))):
                kind, name = draw(st.sampled_from(events))
                target = draw(st.sampled_from([None, *states]))
                assignment = ""
                if variables and kind == "response from" and draw(st.booleans()):
                    assignment = draw(
                        st.sampled_from([f" do {n} := {n} + 1", f" do {n} := 0", f" do {flag} := !{flag}"])
                    )
                goto = f" goto {target}" if target else ""
                lines.append(f"        on {kind} {name}{assignment}{goto}")
            # a way back to the initial state keeps every state able to reach a marked one (rule 3)
            guard = ""
            if guards and draw(st.booleans()):
                options = [flag, f"{n} < 2", f"!{flag} or {n} = 0"] if variables else ["true"]
                guard = " if " + draw(st.sampled_from(options))
            if state not in marked or draw(st.booleans()):
                lines.append(f"        transition{guard} goto {states[0] if states[0] in marked else marked[0]}")
            lines.append("      }")
        lines.append("    }")
        lines.append("  }")
    # requirements
    triggers = [k for _, _, _, ks, _, _, _, _ in components for k in ks]
    triggers += [srv for _, _, _, _, service, srv, _, _ in components if service]
    sensors_all = [s for _, _, ss, _, _, _, _, _ in components for s in ss]
    for _ in range(draw(st.integers(0, 3))):
        name, states, _, _, _, _, _, n = draw(st.sampled_from(components))
        picked = draw(st.lists(st.sampled_from(states), min_size=1, max_size=2, unique=True))
        condition = " or ".join(f"{name}.{s}" for s in picked)
        if variables and draw(st.booleans()):
            condition = f"({condition}) and {name}.{n} {draw(st.sampled_from(['<', '=', '>=']))} 1"
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
