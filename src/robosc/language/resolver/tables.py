"""Name tables of one component, filled before any transition or requirement is resolved."""

from __future__ import annotations

from robosc.language import model as m
from robosc.record import field, record


@record(frozen=False)
class ComponentTables:
    name: str  # the component's name in the robot (its owner label)
    states: dict[str, m.State] = field(default_factory=dict)
    variables: dict[str, m.Variable] = field(default_factory=dict)
    communications: list[m.Communication] = field(default_factory=list)
    # its communications by the names its own transitions use (``go`` for ``bot1.go``)
    local: dict[str, m.Communication] = field(default_factory=dict)
