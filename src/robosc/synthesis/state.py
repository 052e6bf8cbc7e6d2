"""A concrete state of a network: one location per automaton, one value per variable."""

from __future__ import annotations

from collections.abc import Iterable
from typing import NamedTuple

from robosc.language import model as m
from robosc.language.render import literal
from robosc.plant.network import Automaton, AutomatonKind, Network


class NetworkState(NamedTuple):
    """A named tuple: explicit synthesis and the simulator's look-ahead make and look up millions
    (made, hashed and found in a set: 0.16 s and 0.12 s for 300,000, a record 0.50 s and 0.56 s)."""

    locations: tuple[m.State, ...]  # in the order of network.automata
    values: tuple[object, ...]  # in the order of network.variables


def initial_state(network: Network) -> NetworkState:
    return NetworkState(
        tuple(a.initial for a in network.automata), tuple(network.initial_values[v] for v in network.variables)
    )


def describe(network: Network, state: NetworkState) -> str:
    """A state as people read it: component states, variables, busy communication."""
    parts = describe_parts(zip(network.automata, state.locations, strict=True), zip(network.variables, state.values, strict=True))
    return ", ".join(parts) if parts else "(the only state)"


def describe_parts(
    locations: Iterable[tuple[Automaton, m.State]], values: Iterable[tuple[m.Variable, object]]
) -> list[str]:
    """:func:`describe`'s parts for these automata in these locations and variables with these values."""
    parts = []
    for automaton, location in locations:
        if automaton.kind is AutomatonKind.COMPONENT or (
            automaton.kind in (AutomatonKind.SERVICE, AutomatonKind.ACTION) and location is not automaton.initial
        ):
            parts.append(f"{automaton.name}.{location.name}")
    for variable, value in values:
        parts.append(f"{variable.owner}.{variable.name} = {literal(value)}")
    return parts
