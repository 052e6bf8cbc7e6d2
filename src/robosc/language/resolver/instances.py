"""Instances of a component (``component bot[4] ...``), and the expressions that the
quantifiers and ``for`` blocks over them expand into.

A group ``bot`` of N instances becomes N components ``bot1`` .. ``botN``; each instance's
communications are named ``bot1.go`` in the model and live under the instance's ROS
namespace. ``all``/``any`` over a group become a conjunction / disjunction of one term per
instance, ``count`` an :class:`~robosc.language.model.Count`; comparing two instance
variables (``q != r``) is decided while expanding, and the constants it leaves are folded
away, so the expanded model reads as if written out by hand.
"""

from __future__ import annotations

from robosc.language import syntax as s
from robosc.language.checks.topic_names import problem as ros_name_problem
from robosc.language.codes import Code
from robosc.language.resolver.reporter import Reporter
from robosc.record import record

MAX_INSTANCES = 1000  # instances of one component
MAX_EXPANSION = 500_000  # expression nodes that quantifiers and 'for' blocks may make in one file
QUANTIFIERS = ("all", "any", "count")


@record
class Instance:
    """One component to declare: an instance of a group, or a plain component (``group`` None)."""

    name: str
    group: str | None
    index: int | None
    namespace: str | None
    initial: s.Name | None  # the state it starts in instead of the automaton's initial one


def instances(
    syntax: s.LocalComponentSyntax | s.ImportedComponentSyntax, reporter: Reporter, size: int | None = None
) -> list[Instance]:
    """The components that ``syntax`` declares: one, or one per instance; ``size``: how many
    instances a ``component NAME[N]`` has instead of N (asked for on the command line)."""
    name = syntax.name.text
    options = syntax.instances
    if options is None:
        return [Instance(name, None, None, None, None)]
    namespace = None
    if options.namespace is not None:
        namespace = options.namespace.value
        reason = ros_name_problem(namespace) if namespace != "/" else None
        if reason is None and namespace.startswith("~"):
            reason = "a namespace cannot be private ('~')"
        if reason is not None:
            reporter.error(options.namespace.span, f"'{namespace}' is not a valid ROS namespace: {reason}", Code.INSTANCES)
            namespace = None
    if options.count is None:  # a single component with options: `namespace` and `initial` apply to it
        if len(options.initial) > 1:
            reporter.error(
                options.initial[1].span,
                f"'{name}' is one component and starts in one state; {len(options.initial)} are given",
                Code.INSTANCES,
                f"write 'component {name}[{len(options.initial)}]' for that many instances",
            )
        initial = options.initial[0] if options.initial else None
        return [Instance(name, None, None, namespace.rstrip("/") or "/" if namespace else None, initial)]
    count = options.count.value if size is None else size
    asked = "" if size is None else f" (--instances {name}={size})"
    if not 1 <= count <= MAX_INSTANCES:
        reporter.error(
            options.count.span,
            f"{count} instances of '{name}'{asked}: a component has from 1 to {MAX_INSTANCES} instances",
            Code.INSTANCES if count < 1 else Code.LIMIT,
        )
        return []
    if options.initial and len(options.initial) != count:
        reporter.error(
            options.initial[min(len(options.initial), count) - 1].span if len(options.initial) > count else options.span,
            f"{len(options.initial)} initial states for {count} instances of '{name}'{asked}: give one per instance, "
            "in order",
            Code.INSTANCES,
        )
    prefix = "" if namespace is None else namespace.rstrip("/") + "/"
    found = []
    for index in range(1, count + 1):
        # too few given (reported): the last one for the rest, so that nothing else is reported
        initial = options.initial[min(index, len(options.initial)) - 1] if options.initial else None
        found.append(Instance(f"{name}{index}", name, index, f"{prefix}{name}{index}", initial))
    return found


def ros_identifier(
    syntax: s.CommunicationSyntax, instance: Instance, reporter: Reporter
) -> tuple[str, str | None]:
    """A communication's name in the model and its ROS name (None: its name, as written)."""
    local = syntax.name.text
    identifier = syntax.identifier.value if syntax.identifier is not None else None
    if instance.namespace is None:
        return local, identifier
    name = f"{instance.name}.{local}" if instance.group is not None else local
    if identifier is not None and identifier[:1] in ("/", "~"):
        if instance.group is None:
            return name, identifier  # an absolute name ignores the namespace, as in ROS
        assert syntax.identifier is not None
        reporter.error(
            syntax.identifier.span,
            f"'{identifier}' is {'an absolute' if identifier[0] == '/' else 'a private'} ROS name: every instance "
            f"of '{instance.group}' would use the same one",
            Code.INSTANCES,
            f"write it relative ('{identifier.lstrip('/~')}'): each instance then has its own, under its namespace",
        )
    base = identifier.lstrip("/~") if identifier is not None else local
    namespace = instance.namespace.rstrip("/")
    return name, f"{namespace}/{base}" if namespace else f"/{base}"
