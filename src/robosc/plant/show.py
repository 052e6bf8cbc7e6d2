"""A readable listing of a network, for debugging (``robosc synthesize --show-network``)."""

from __future__ import annotations

from robosc.language.render import literal, render
from robosc.plant.network import Network


def show_network(network: Network) -> str:
    lines = [f"network of robot {network.model.name}", ""]
    lines.append("events:")
    for event in network.events:
        lines.append(f"  {'controllable  ' if event.controllable else 'uncontrollable'} {event.name}")
    lines.append("")
    lines.append("variables:")
    for variable in network.variables:
        domain = network.domains[variable]
        if isinstance(domain, range):
            values = f"{domain.start}..{domain.stop - 1}"
        else:
            values = "{" + ", ".join(literal(v) for v in domain) + "}"
        start = literal(network.initial_values[variable])
        lines.append(f"  {variable.owner}.{variable.name} in {values} = {start}")
    for automaton in network.automata:
        lines.append("")
        lines.append(f"{automaton.kind.value} {automaton.name}:")
        for location in automaton.locations:
            flags = " ".join(
                f for f, on in (("initial", location is automaton.initial), ("marked", location.marked)) if on
            )
            lines.append(f"  location {location.name}{' (' + flags + ')' if flags else ''}")
            for edge in automaton.edges:
                if edge.source is not location:
                    continue
                text = f"    --{edge.event.name}--> {edge.target.name}"
                if edge.guard is not None:
                    text += f" if {render(edge.guard)}"
                for update in edge.updates:
                    value = render(update.value) if update.value is not None else "<received>"
                    text += f" do {update.variable.name} := {value}"
                lines.append(text)
    lines.append("")
    lines.append("requirements:")
    for requirement in network.requirements:
        lines.append(f"  {requirement.event.name} only if {render(requirement.condition)}  ({requirement.description})")
    return "\n".join(lines)
