# -*- coding: utf-8 -*-
"""Tasks given to a fleet at run time, and the coordinator's choice with a purpose.

A task names the locations of a robot's automaton it must reach in turn (its *stops*, e.g.
``["shelf", "depot"]``: fetch from the shelf, bring it to the depot), and optionally the robot
(``bot2``) or the group of instances (``bot``) that is to do it. :class:`Dispatcher` keeps the
queue, assigns queued tasks to idle robots able to do them, follows each task (queued,
assigned, done, failed with why) and chooses, among the controllable events the supervisor
allows, the one to send:

1. internal events (no command to anyone) first, as they come;
2. else a command that brings a robot nearer to its next stop (the fewest edges of its own
   automaton, ``routes.py``), of the robot that has waited longest since it last got on (was
   given its task or sent such a command);
3. else a command that brings a shared component (a door, a lift: a component that is no
   robot) nearer to a location where some robot's blocked step would be allowed;
4. else, when no robot has a task, a command that brings a shared component back to its
   initial location. While the fleet works a shared component stays where a robot last
   needed it: a door that robots pass one after another stays open between them, instead of
   closing behind each one and opening again when the next one comes out.

Nothing else is sent: a robot without a task stays where it is if that is one of its marked
locations, and else goes to the nearest one (its home). Every event chosen is one the
supervisor allows now: the policy only narrows the choice, so the guarantees stay the
supervisor's. ``policy="random"`` keeps the uniform random choice among all of them.

A task is refused at once (failed, with the reason) when no robot it may go to has all its
stops in its automaton, or cannot get from one stop to the next there. Assignment: the queue
in order; each task to the idle able robot nearest its first stop, then the one with the
fewest tasks done, then the one idle longest."""

from __future__ import absolute_import, annotations

from collections import Counter, OrderedDict
from typing import Any, Callable, Dict, List, Optional, Sequence, Set, Tuple

from .routes import Routes

QUEUED, ASSIGNED, DONE, FAILED = "queued", "assigned", "done", "failed"
POLICIES = ("purpose", "random")
KEPT = 1000  # finished tasks kept for the queue's readers (the oldest are forgotten)
MAX_STOPS = 100


class Task(object):
    """One task and where it is."""

    __slots__ = ("assigned_at", "by", "done_at", "id", "queued_at", "reached", "robot", "state", "stops", "why")

    def __init__(self, id: str, stops: Tuple[str, ...], robot: Optional[str], now: float) -> None:
        self.id, self.stops, self.robot = id, stops, robot  # robot: a robot or a group asked for, or None
        self.state, self.why = QUEUED, ""
        self.by: Optional[str] = None  # the robot doing it
        self.reached = 0  # stops reached so far
        self.queued_at = now
        self.assigned_at: Optional[float] = None
        self.done_at: Optional[float] = None

    def as_dict(self) -> Dict[str, Any]:
        return {
            "id": self.id, "stops": list(self.stops), "robot": self.robot, "state": self.state, "why": self.why,
            "by": self.by, "reached": self.reached, "queued_at": self.queued_at, "assigned_at": self.assigned_at,
            "done_at": self.done_at,
        }


class Dispatcher(object):
    """The tasks of the fleet that ``supervisor`` (a generated robot with ``SHAPES`` and
    ``ROUTES``) coordinates, and its choice (see the module's description). ``on_change`` is
    called with a task's :meth:`Task.as_dict` whenever its state changes."""

    def __init__(self, supervisor: Any, policy: str = "purpose",
                 on_change: Optional[Callable[[Dict[str, Any]], Any]] = None,
                 clock: Optional[Callable[[], float]] = None) -> None:
        if policy not in POLICIES:
            raise ValueError("no policy %r (%s)" % (policy, ", ".join(POLICIES)))
        self.supervisor, self.policy, self.on_change = supervisor, policy, on_change
        self.clock: Callable[[], float] = clock if clock is not None else supervisor.clock  # stamps and waits
        self.routes = Routes(getattr(supervisor, "SHAPES", ()), getattr(supervisor, "ROUTES", ()))
        self.groups = self.routes.groups()
        self.robots = [name for members in self.groups.values() for name in members]
        taken = set(self.robots)
        commands = set(supervisor.CONTROLLABLE)
        self.shared = [name for name in self.routes.order
                       if name not in taken and self.routes.route[name].events() & commands]
        self.tasks: "OrderedDict[str, Task]" = OrderedDict()
        self.doing: Dict[str, Task] = {}  # robot -> its task
        self.since: Dict[str, float] = dict((robot, 0.0) for robot in self.robots)  # when it last got on
        self.done: "Counter[str]" = Counter()  # robot -> tasks done
        self._numbers = 0
        self._pending = False  # a queued task may be assignable now

    # ---- the queue ------------------------------------------------------------------

    def submit(self, stops: Sequence[str], robot: Optional[str] = None, id: Optional[str] = None) -> Task:
        """Queue a task (assigned at the next :meth:`observe`), or refuse it at once: the task
        is returned failed, with why."""
        task = self._new(id, tuple(str(s) for s in stops) if isinstance(stops, (list, tuple)) else (), robot)
        why = self._refusal(task, stops)
        if task.id in self.tasks:
            why = "a task named %r was given already" % task.id
        return self._enter(task, why)

    def refuse(self, why: str, id: Optional[str] = None) -> Task:
        """Note a task that could not even be read as failed, with why."""
        return self._enter(self._new(id, (), None), why)

    def _new(self, id: Optional[str], stops: Tuple[str, ...], robot: Optional[str]) -> Task:
        self._numbers += 1
        return Task(str(id) if id else "task%d" % self._numbers, stops, robot, self.clock())

    def _enter(self, task: Task, why: str) -> Task:
        """Keep ``task`` (under a name of its own), queued or, with ``why``, failed."""
        if task.id in self.tasks:
            task.id = "%s#%d" % (task.id, self._numbers)
        self.tasks[task.id] = task
        if why:
            self._finish(task, FAILED, why)
        else:
            self._pending = True
            self._changed(task)
        self._forget()
        return task

    def _refusal(self, task: Task, stops: Any) -> str:
        if not self.robots:
            return "this model has no group of robots (component NAME[N]) to give tasks to"
        if not isinstance(stops, (list, tuple)) or not task.stops:
            return "a task names one or more locations to reach in turn (stops)"
        if len(task.stops) > MAX_STOPS:
            return "a task has at most %d stops" % MAX_STOPS
        if task.robot is not None and task.robot not in self.routes.route:
            return "no robot or group %r (robots: %s)" % (task.robot, ", ".join(self.robots))
        whys = [self._unable(robot, task.stops) for robot in self._candidates(task)]
        return "" if "" in whys else whys[0]

    def _candidates(self, task: Task) -> List[str]:
        if task.robot is None:
            return self.robots
        return self.groups.get(task.robot, [task.robot])

    def _unable(self, robot: str, stops: Tuple[str, ...]) -> str:
        """Why ``robot`` can never do a task with these stops ("" if it can)."""
        route = self.routes.route[robot]
        if robot not in self.since:
            return "%s is no robot of a group (robots: %s)" % (robot, ", ".join(self.robots))
        who = route.group or robot
        for stop in stops:
            if stop not in route.locations:
                return "%r is no location of %s (its locations: %s)" % (stop, who, ", ".join(sorted(route.locations)))
            if stop in route.never:
                return "the supervisor never lets %s reach %s (robosc synthesize says why)" % (who, stop)
        here = route.initial
        for stop in stops:
            if not self.routes.reaches(robot, here, stop):
                return "%s cannot get from %s to %s" % (who, here, stop)
            here = stop
        return ""

    def _finish(self, task: Task, state: str, why: str = "") -> None:
        task.state, task.why = state, why
        task.done_at = self.clock()
        if task.by is not None and self.doing.get(task.by) is task:
            del self.doing[task.by]
            self.since[task.by] = task.done_at
            self._pending = True
        self._changed(task)

    def _changed(self, task: Task) -> None:
        if self.on_change is not None:
            try:
                self.on_change(task.as_dict())
            except Exception as error:  # a broken listener must not stop the coordinator
                self.supervisor.warn("a task listener failed: %s: %s" % (type(error).__name__, error), "tasks")

    def _forget(self) -> None:
        finished = [t.id for t in self.tasks.values() if t.state in (DONE, FAILED)]
        for name in finished[: max(0, len(finished) - KEPT)]:
            del self.tasks[name]

    def queue(self) -> List[Dict[str, Any]]:
        """Every task kept, in the order given."""
        return [task.as_dict() for task in self.tasks.values()]

    def counts(self) -> Dict[str, int]:
        out = dict((state, 0) for state in (QUEUED, ASSIGNED, DONE, FAILED))
        for task in self.tasks.values():
            out[task.state] += 1
        return out

    # ---- following the robots -----------------------------------------------------

    def _where(self, component: str) -> Optional[str]:
        """The component's location, or None while it is unconfirmed."""
        route = self.routes.route[component]
        if route.field in self.supervisor.unconfirmed:
            return None
        return str(getattr(self.supervisor, route.field))

    def observe(self) -> None:
        """Note the stops the robots reached, finish what is done, assign what is queued."""
        for robot, task in list(self.doing.items()):
            here = self._where(robot)
            while here is not None and task.reached < len(task.stops) and task.stops[task.reached] == here:
                task.reached += 1
                self.since[robot] = self.clock()
            if task.reached == len(task.stops):
                self.done[robot] += 1
                self._finish(task, DONE)
        if self._pending and len(self.doing) < len(self.robots):
            self._assign()

    def _assign(self) -> None:
        self._pending = False
        for task in list(self.tasks.values()):
            if task.state != QUEUED:
                continue
            best: Optional[Tuple[Any, ...]] = None
            for order, robot in enumerate(self._candidates(task)):
                here = self._where(robot)
                if here is None:
                    self._pending = True  # to be tried again once the robot has said where it is
                if robot in self.doing or here is None or self._unable(robot, task.stops):
                    continue
                far = self.routes.distance(robot, (task.stops[0],)).get(here)
                if far is None:
                    continue
                key = (far, self.done[robot], self.since[robot], order)
                if best is None or key < best[0]:
                    best = (key, robot)
            if best is not None:
                robot = best[1]
                task.state, task.by, task.assigned_at = ASSIGNED, robot, self.clock()
                self.doing[robot] = task
                self.since[robot] = task.assigned_at
                self._changed(task)

    def targets(self, robot: str, here: str) -> Optional[Tuple[str, ...]]:
        """Where ``robot`` (at ``here``) is to go next: its task's next stop, or home (its
        marked locations) when it has no task and is not home; None: it stays."""
        task = self.doing.get(robot)
        if task is not None:
            return (task.stops[task.reached],)
        marked = self.routes.route[robot].marked
        return None if here in marked or not marked else tuple(marked)

    def waiting(self) -> Dict[str, float]:
        """Each robot with a task: the seconds since it last got on."""
        now = self.clock()
        return dict((robot, now - self.since[robot]) for robot in self.doing)

    # ---- the choice ---------------------------------------------------------------

    def choose(self, enabled: Sequence[Callable[..., Optional[str]]]) -> Optional[Callable[..., Optional[str]]]:
        """The allowed event to perform now (see the module's description), or None; the
        caller observed (:meth:`observe`) first."""
        supervisor = self.supervisor
        names: Dict[str, Callable[..., Optional[str]]] = {}
        for perform in enabled:
            if perform.__name__ not in supervisor.REQUESTS:
                return perform
            names[supervisor.BY_METHOD[perform.__name__].name] = perform
        best: Optional[Tuple[Tuple[float, int], str, Callable[..., Optional[str]]]] = None
        blocked: Set[str] = set()
        for order, robot in enumerate(self.robots):
            here = self._where(robot)
            goal = self.targets(robot, here) if here is not None else None
            if goal is None:
                continue
            steps = self.routes.steps(robot, here, goal)  # type: ignore[arg-type]
            now = [step for step in steps if step in names]
            if not now:
                blocked.update(steps)
                continue
            key = (self.since[robot], order)
            if best is None or key < best[0]:
                best = (key, robot, names[now[0]])
        if best is not None:
            self.since[best[1]] = self.clock()
            return best[2]
        if supervisor.unconfirmed:
            return None  # what would help whom is not known
        for component in self.shared:
            here = self._where(component)
            wanted = self._wanted(component, here, blocked) if blocked else set()
            if not wanted and self.doing:
                continue  # while the fleet works it stays where a robot last needed it
            rest = wanted or set([self.routes.route[component].initial])
            for step in self.routes.steps(component, here, rest):  # type: ignore[arg-type]
                if step in names:
                    return names[step]
        return None

    def _wanted(self, component: str, here: Any, blocked: Set[str]) -> Set[str]:
        """The locations of the shared ``component`` at which one of the ``blocked`` steps
        would be allowed, all else as it is."""
        supervisor = self.supervisor
        route = self.routes.route[component]
        wanted: Set[str] = set()
        try:
            for location in route.locations:
                if location == here:
                    continue
                setattr(supervisor, route.field, location)
                allowed = set(supervisor.BY_METHOD[p.__name__].name for p in supervisor._allowed())
                if allowed & blocked:
                    wanted.add(location)
        finally:
            setattr(supervisor, route.field, here)
        return wanted
