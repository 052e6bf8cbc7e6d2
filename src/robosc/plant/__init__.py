"""The plant stage: a checked model to a network of extended finite automata
(SEMANTICS.md sections 1-4). See :func:`robosc.plant.build.build_network`."""

from robosc.plant.build import build_network
from robosc.plant.network import Automaton, Edge, Event, EventKind, Network, Requirement, Update

__all__ = ["Automaton", "Edge", "Event", "EventKind", "Network", "Requirement", "Update", "build_network"]
