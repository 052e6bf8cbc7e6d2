"""The documented Python API of robosc. The CLI is a thin layer over these functions.

>>> from robosc.api import check_file
>>> result = check_file("examples/maze_solver.rscd")
>>> result.ok, result.model.name
(True, 'MazeSolver')
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, TextIO

from robosc.language.checks import run_checks
from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, render_text, sort_key
from robosc.language.loader import InputError, LibraryFinder, read_source
from robosc.language.model import Model
from robosc.language.parser import parse_source
from robosc.language.resolver import resolve
from robosc.language.source import SourceFile
from robosc.record import field, record

if TYPE_CHECKING:
    from robosc.codegen.plan import Plan
    from robosc.debug.simulator import Simulator
    from robosc.language.reparse import Reparser
    from robosc.sim.report import Report
    from robosc.sim.world import World
    from robosc.synthesis.compare import Comparison
    from robosc.synthesis.finish import Finish
    from robosc.synthesis.options import SynthesisOptions
    from robosc.synthesis.progress import Progress
    from robosc.synthesis.result import Restriction, SynthesisResult

__all__ = [
    "CheckResult",
    "InputError",
    "ModelError",
    "SynthesisResult",
    "check_file",
    "check_finish",
    "check_text",
    "enforce_finish",
    "format_text",
    "load_model",
    "plan_supervisor",
    "restriction",
    "run_world",
    "simulator",
    "supervisor_module",
    "synthesize_file",
    "synthesize_model",
]


@record
class CheckResult:
    """The outcome of reading and checking one model file.

    ``model`` is the checked model when there are no errors (warnings allowed),
    otherwise None. ``sources`` holds the text of every file read (the model and
    its libraries), for rendering diagnostics.
    """

    model: Model | None
    diagnostics: tuple[Diagnostic, ...]
    sources: dict[str, SourceFile] = field(default_factory=dict, repr=False)
    # each name that resolved and the model object it names (with a span): what editors
    # need for definitions and references
    references: tuple[tuple[Any, Any], ...] = field(default=(), compare=False, repr=False)

    @property
    def ok(self) -> bool:
        return not any(d.is_error for d in self.diagnostics)

    @property
    def errors(self) -> tuple[Diagnostic, ...]:
        return tuple(d for d in self.diagnostics if d.is_error)

    def render(self, columns: int | None = None) -> str:
        """All diagnostics as text: ``path:line:col: error: message``, source line, caret;
        with ``columns``, wrapped to that width."""
        return "\n".join(render_text(d, self.sources, columns) for d in self.diagnostics)


class ModelError(Exception):
    """Raised by :func:`load_model` when a model has errors."""

    def __init__(self, result: CheckResult) -> None:
        super().__init__(result.render())
        self.result = result


def _search_paths(path: str, search_paths: Sequence[str | Path]) -> list[Path]:
    return [Path(path).parent if path != "<text>" else Path("."), *(Path(p) for p in search_paths)]


def _check(
    source: SourceFile,
    search_paths: Sequence[str | Path],
    reparser: Reparser | None = None,
    sizes: Mapping[str, int] | None = None,
) -> CheckResult:
    sources = {source.path: source}
    parsed = parse_source(source) if reparser is None else reparser.parse(source)
    if parsed.syntax is None:
        return CheckResult(None, parsed.diagnostics, sources)
    finder = LibraryFinder(_search_paths(source.path, search_paths), sources)
    resolved = resolve(parsed.syntax, source.path, finder, sizes)
    diagnostics = list(resolved.diagnostics)
    if not any(d.code is Code.LIMIT for d in diagnostics):  # else the model is a part, maybe a huge one
        diagnostics += [d for d in run_checks(resolved.model) if d not in diagnostics]
    diagnostics.sort(key=sort_key)
    ok = not any(d.is_error for d in diagnostics)
    return CheckResult(resolved.model if ok else None, tuple(diagnostics), sources, resolved.references)


def check_text(
    text: str,
    path: str = "<text>",
    search_paths: Sequence[str | Path] = (),
    reparser: Reparser | None = None,
    sizes: Mapping[str, int] | None = None,
) -> CheckResult:
    """Parse, resolve and check model text. Libraries are looked up next to ``path``
    and on ``search_paths``. Never raises for bad input: problems are diagnostics.
    A :class:`~robosc.language.reparse.Reparser` given for successive versions of one file
    (an editor's) parses only what changed; the result is the same. ``sizes``: how many
    instances a ``component NAME[N]`` has instead of N, by NAME (``{"bot": 8}``: a fleet of 8
    without editing the model)."""
    return _check(SourceFile(path, text), search_paths, reparser, sizes)


def check_file(
    path: str | Path, search_paths: Sequence[str | Path] = (), sizes: Mapping[str, int] | None = None
) -> CheckResult:
    """Read and check a model file (``sizes`` as for :func:`check_text`). Raises
    :class:`InputError` if it cannot be read."""
    return _check(read_source(path), search_paths, sizes=sizes)


def load_model(
    path: str | Path, search_paths: Sequence[str | Path] = (), sizes: Mapping[str, int] | None = None
) -> Model:
    """The checked model of a file (``sizes`` as for :func:`check_text`), or :class:`ModelError`
    carrying the diagnostics."""
    result = check_file(path, search_paths, sizes)
    if result.model is None:
        raise ModelError(result)
    return result.model


def format_text(text: str, path: str = "<text>") -> str | CheckResult:
    """The model in robosc's canonical layout, comments kept; a :class:`CheckResult`
    with the syntax error when the text does not parse."""
    source = SourceFile(path, text)
    parsed = parse_source(source)
    if parsed.syntax is None:
        return CheckResult(None, parsed.diagnostics, {path: source})
    from robosc.language.formatter import format_syntax

    return format_syntax(parsed.syntax)


def synthesize_model(
    model: Model,
    method: str = "symbolic",
    options: SynthesisOptions | None = None,
    progress: Callable[[Progress], Any] | None = None,
) -> SynthesisResult:
    """The supervisor of a checked robot model.

    ``result.ok`` tells whether one exists; ``result.guards`` gives, for each
    controllable event, the user's condition and the condition synthesis added;
    ``result.allows(event, state)`` answers for a concrete network state;
    ``result.explanation`` says why synthesis failed. ``options``
    (:class:`robosc.synthesis.options.SynthesisOptions`) tune the symbolic method's
    speed and memory, never its result. ``progress`` is called with a
    :class:`robosc.synthesis.progress.Progress` every quarter of a second or so while the
    symbolic method works (phase, round, steps, BDD nodes, seconds), for a display.
    """
    from robosc.plant import build_network
    from robosc.synthesis.explicit import synthesize_explicit
    from robosc.synthesis.methods import synthesize_symbolic
    from robosc.synthesis.options import DEFAULT

    network = build_network(model)
    if method == "explicit":
        return synthesize_explicit(network)
    if method != "symbolic":
        raise ValueError(f"unknown synthesis method '{method}' (symbolic or explicit)")
    return synthesize_symbolic(network, options or DEFAULT, progress)


def cross_check(
    model: Model, options: SynthesisOptions | None = None
) -> tuple[SynthesisResult, SynthesisResult, Comparison]:
    """Explicit-state synthesis of a checked model, the symbolic method (``options``: monolithic
    or counted) on the same network, and how they compare state by state and event by event
    (:class:`robosc.synthesis.compare.Comparison`; a counted result's states are orbits, and the
    explicit states are counted so)."""
    from robosc.plant import build_network
    from robosc.synthesis.compare import compare
    from robosc.synthesis.explicit import synthesize_explicit
    from robosc.synthesis.methods import synthesize_symbolic
    from robosc.synthesis.options import DEFAULT

    network = build_network(model)
    explicit = synthesize_explicit(network)
    symbolic = synthesize_symbolic(network, options or DEFAULT)
    return explicit, symbolic, compare(explicit, symbolic)


def restriction(result: SynthesisResult, event: str) -> Restriction | None:
    """Why synthesis added a condition to the controllable event ``event`` (its name): a
    shortest run to a state where the supervisor holds it back, where it would lead and what
    would go wrong from there, with fixes; None when synthesis added nothing to it. Computed
    on request (``robosc synthesize`` prints it under "why synthesis added these conditions")."""
    from robosc.synthesis.restrictions import restriction as made

    return made(result, event)


def check_finish(result: SynthesisResult, options: SynthesisOptions | None = None) -> Finish:
    """Whether every robot of ``result``'s fleet can always get to each place it goes to under
    the supervisor, not just the fleet back to a marked state together
    (:class:`robosc.synthesis.finish.Finish`: ``ok``, and for each robot that can be starved a
    shortest run to where it cannot and the loop the others can then go round)."""
    from robosc.synthesis.finish import check_finish as check
    from robosc.synthesis.options import DEFAULT

    return check(result, options or DEFAULT)


def enforce_finish(
    result: SynthesisResult, options: SynthesisOptions | None = None, finish: Finish | None = None
) -> SynthesisResult:
    """``result``'s supervisor made to keep every robot able to finish (:func:`check_finish`;
    ``finish``: its answer, where it was asked already): the maximally permissive one under
    which, besides, each robot can always get to each of its places (the monolithic method);
    ``result`` itself where no robot can be starved."""
    from robosc.synthesis.finish import finish_supervisor
    from robosc.synthesis.options import DEFAULT

    return finish_supervisor(result, finish or check_finish(result, options), options or DEFAULT)


def synthesize_file(
    path: str | Path, search_paths: Sequence[str | Path] = (), sizes: Mapping[str, int] | None = None
) -> SynthesisResult:
    """Load, check and synthesize a model file (``sizes`` as for :func:`check_text`; raises
    :class:`ModelError` on model errors)."""
    return synthesize_model(load_model(path, search_paths, sizes))


def __getattr__(name: str) -> Any:
    if name == "SynthesisResult":  # re-exported, imported on first use (it loads the plant stage)
        from robosc.synthesis.result import SynthesisResult

        return SynthesisResult
    raise AttributeError(f"module 'robosc.api' has no attribute '{name}'")


def plan_supervisor(result: SynthesisResult) -> Plan:
    """Lay out a successful synthesis result for code generation and simulation
    (``robosc.codegen.ros.generate`` raises ``RosError``, with the model span, when the
    model cannot run on ROS as it is, e.g. a service that links no interface)."""
    from robosc.codegen.plan import plan

    return plan(result)


def supervisor_module(result: SynthesisResult) -> str:
    """The stand-alone Python supervisor module (Python 3.8+, standard library only)."""
    from robosc.codegen.module import render_module

    return render_module(plan_supervisor(result))


def simulator(result: SynthesisResult, seed: int | None = None, log: TextIO | None = None) -> Simulator:
    """A simulator running the generated supervisor, checking each step against ``result``."""
    from robosc.debug.simulator import Simulator

    return Simulator(result, plan_supervisor(result), seed=seed, log=log)


def run_world(
    world: str | Path | World,
    result: SynthesisResult,
    ros: int | None = None,
    robots: int | None = None,
    timeout: float | None = None,
    speed: float = 4.0,
    rate: float = 10.0,
    seed: int = 0,
    folder: Path | None = None,
    domain: int | None = None,
    page: str | None = None,
    on_start: Callable[[object], None] | None = None,
    plan: Plan | None = None,
    on_note: Callable[[str], None] | None = None,
    tasks: int = 1,
    on_event: Callable[[dict[str, Any]], None] | None = None,
    on_step: Callable[[Any], None] | None = None,
    policy: str = "purpose",
) -> Report:
    """Drive the robots of a 2D world (a world file or a loaded one) with the controller of a
    successful synthesis ``result``: on ROS ``ros`` (1 or 2: the generated package on a private
    graph, paced at ``speed`` times real time) or, with None, in this process.

    In a world with a goal, ``robots`` robots (default 1) each have a controller of their own
    and the run ends when every robot reached the goal (``report.ok``), one touched something,
    or ``timeout`` simulated seconds passed (default 300). In a fleet's world (one with
    ``fleet``) the model is the fleet's coordinator (robots: the model's, by default) and the
    run ends when the tasks the world gives (``tasks`` per robot, its ``stops`` each) are done,
    at a collision, a deadlock or the time-out (default 300 s per robot and task); ``policy``
    is how the coordinator chooses among what its supervisor allows ("purpose": for the tasks,
    fairly; "random": at random); ``on_event(record)`` hears the coordinator's events in
    this process and ``on_step(world)`` is called after every step. Either way the result is
    one :class:`robosc.sim.report.Report`.

    Raises ``robosc.sim.world.WorldError`` for a bad world file,
    ``robosc.sim.session.SessionError`` when the middleware does not come up,
    ``robosc.sim.run.Misfit`` when the model sends none of the commands a world's robots obey
    and ``robosc.sim.fleet.FleetMisfit`` when the model's fleet does not fit the world.
    ``folder`` keeps the package, logs and event logs (else a temporary one is used for ROS
    runs); ``on_start(graph)`` is called once the ROS nodes are started; ``page`` is the live
    view's page the package carries (robosc.debug.live.live_page); ``plan`` is
    the result's plan when it is made already; ``on_note`` hears of the model's topics the
    simulator does not have."""
    from robosc.debug.simulator import load_module
    from robosc.sim.run import fit, run_local, run_ros
    from robosc.sim.world import load_world

    loaded = world if not isinstance(world, str | Path) else load_world(world)
    plan = plan if plan is not None else plan_supervisor(result)
    module = load_module(plan)
    if loaded.fleet is None:
        for note in fit(loaded, module.Robot.COMMUNICATIONS):
            if on_note is not None:
                on_note(note)
    if ros is None:
        return run_local(
            loaded, module, robots, timeout, rate, seed, folder, tasks, on_event=on_event, on_step=on_step,
            policy=policy,
        )
    return run_ros(
        loaded, plan, module, ros, robots, timeout, speed, rate, seed, folder, domain, on_step=on_step,
        on_start=on_start, page=page, tasks=tasks, policy=policy,
    )
