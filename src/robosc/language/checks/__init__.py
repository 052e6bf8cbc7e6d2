"""The static rules of LANGUAGE.md section 5, one module per rule.

Each module has ``check(model) -> Iterator[Diagnostic]``. Rule 14 (every
reference resolves) and the expression type rules are enforced while
resolving, in :mod:`robosc.language.resolver`.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator

from robosc.language.checks import (
    constant_values,
    enum_default,
    enum_source,
    enum_values,
    implicit_start,
    initial_state,
    instances,
    integer_range,
    interface_links,
    limits,
    marked_reachable,
    no_array,
    no_data_to_request,
    object_variables,
    one_behaviour,
    own_variables,
    package_name,
    provide_direction,
    result_types,
    several_outcomes,
    shared_topics,
    synthesis_types,
    topic_names,
    uncontrollable_requirements,
    unique_names,
    variable_ranges,
)
from robosc.language.diagnostics import Diagnostic, once_per_place
from robosc.language.model import Model

Check = Callable[[Model], Iterator[Diagnostic]]

CHECKS: tuple[Check, ...] = (
    unique_names.check,  # rule 1
    initial_state.check,  # rule 2
    marked_reachable.check,  # rule 3
    one_behaviour.check,  # rule 4
    result_types.check,  # rule 5
    no_data_to_request.check,  # rule 6
    own_variables.check,  # rule 7
    provide_direction.check,  # rule 8
    integer_range.check,  # rule 9
    synthesis_types.check,  # rule 10
    enum_source.check,  # rule 11
    interface_links.check,  # rule 12
    shared_topics.check,  # rule 13 (warning)
    topic_names.check,  # rule 15
    enum_default.check,  # section 4: exactly one default rule per enum
    constant_values.check,  # a constant divisor of zero can never be computed
    enum_values.check,  # an enum value is named by one rule
    no_array.check,  # arrays only inside objects (variables, communications, synthesis inputs)
    object_variables.check,  # no variable of object type
    variable_ranges.check,  # constants in a variable's range (warning outside synthesis)
    implicit_start.check,  # warning: an enum variable read with no initial value
    uncontrollable_requirements.check,  # warning: a requirement on what the robot sends
    several_outcomes.check,  # warning: an event with several outcomes, and what tells them apart
    limits.check,  # sizes synthesis cannot represent
    package_name.check,  # a robot's name names a ROS package: a letter first
    instances.check,  # instance and group names clash with no other
)


def run_checks(model: Model) -> list[Diagnostic]:
    """Every rule's diagnostics; a mistake inside a component with instances is found in each
    instance, and said once."""
    return list(once_per_place([diagnostic for check in CHECKS for diagnostic in check(model)]))
