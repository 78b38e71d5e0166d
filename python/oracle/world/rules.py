"""Task inference for the kitchen world: preconditions, effects, available tasks and repair.

The rules live in ``ontology/kitchen-world.yaml`` (PDDL-like, with a fixed vocabulary of
predicates and effects implemented here; ``worldfile`` reads the file). ``World.available(state)`` lists every task call whose
preconditions hold, as EDAN's task inference does (thesis 2.2); ``World.repair`` inserts the
missing intermediate tasks in front of an action that is not yet feasible (thesis 5.2).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path

from oracle.chains import TaskCall, parse_call
from oracle.errors import ChainSyntaxError, NeemOracleError, WorldError
from oracle.world.state import HAND, ObjectSpec, State, blocker, reachable

# a compiled condition: test(state, first argument, second argument, reach) -> holds
Reach = Callable[[str], bool]
Test = Callable[[State, str, str, Reach], bool]



#: Predicate and effect signatures: "o" is a task parameter (an object), "l" a literal word.
PREDICATES: dict[str, str] = {
    "hand_free": "",
    "holding": "o",
    "reachable": "o",
    "tagged": "ol",
    "opened": "o",
    "closed": "o",
    "switched_on": "o",
    "switched_off": "o",
    "accepts": "oo",
    "distinct": "oo",
}
EFFECTS: dict[str, str] = {
    "grasp": "o",
    "put": "oo",
    "open": "o",
    "close": "o",
    "switch_on": "o",
    "switch_off": "o",
}



@dataclass(frozen=True)
class Condition:
    """One precondition or effect atom, e.g. ``holding(source)``; args are parameters or literals."""

    name: str
    args: tuple[str, ...]
    signature: str

    def __str__(self) -> str:
        return f"{self.name}({', '.join(self.args)})" if self.args else self.name

    def params(self) -> frozenset[str]:
        return frozenset(a for a, kind in zip(self.args, self.signature) if kind == "o")

    def bind(self, binding: Mapping[str, str]) -> list[str]:
        """The arguments with parameters replaced by objects; literals stay as written."""
        return [binding[a] if kind == "o" else a for a, kind in zip(self.args, self.signature)]


@dataclass(frozen=True)
class TaskRule:
    name: str
    params: tuple[str, ...]
    requires: tuple[Condition, ...]
    effects: tuple[Condition, ...]


@dataclass(frozen=True)
class Failure:
    """Why an action is not feasible: the first failing precondition, bound to objects."""

    call: TaskCall
    condition: Condition
    bound: tuple[str, ...]

    def __str__(self) -> str:
        inner = ", ".join(self.bound)
        return f"{self.call} is not feasible: {self.condition.name}({inner}) does not hold"


class World:
    """Objects and task rules of one world file; stateless apart from the loaded definitions."""

    def __init__(self, objects: Mapping[str, ObjectSpec], tasks: Mapping[str, TaskRule], park: str, source: Path):
        self.objects = dict(objects)
        self.tasks = dict(tasks)
        self.park = park
        self.source = source
        self._names = tuple(self.objects)
        self._affording = {
            task: tuple(name for name, spec in self.objects.items() if task in spec.affords) for task in self.tasks
        }
        # available() checks conditions on the first argument before it binds the second, and
        # binds the second only to objects that pass the conditions that do not depend on state.
        self._compiled: dict[str, tuple[tuple[Test, ...], tuple[Test, ...], tuple[str, ...] | None]] = {}
        for task, rule in self.tasks.items():
            first = frozenset(rule.params[:1])
            early = tuple(self._compile(c, rule.params) for c in rule.requires if c.params() <= first)
            late = tuple(self._compile(c, rule.params) for c in rule.requires if not c.params() <= first)
            candidates = None
            if len(rule.params) == 2:
                candidates = tuple(y for y in self._names if self._could_bind(rule, y))
            self._compiled[task] = (early, late, candidates)

    # --- queries ------------------------------------------------------------------------------
    def initial_state(self) -> State:
        """Table 5.1: every item where its ``at`` puts it, containers closed, appliances off."""
        location = {name: spec.at for name, spec in self.objects.items() if spec.at is not None}
        return State(location)

    def check_call(self, call: TaskCall | str) -> TaskCall:
        """Parse and validate names and arity against the world; raise WorldError otherwise."""
        if isinstance(call, str):
            call = parse_call(call)
        rule = self.tasks.get(call.task)
        if rule is None:
            raise WorldError(f"{self.source}: no task {call.task!r} (in action {call}); known: {', '.join(self.tasks)}")
        if len(call.args) != len(rule.params):
            raise ChainSyntaxError(
                f"action {call}: task {call.task!r} takes {len(rule.params)} object(s) ({', '.join(rule.params)})"
            )
        for arg in call.args:
            if arg not in self.objects:
                raise WorldError(f"{self.source}: no object {arg!r} (in action {call})")
        return call

    def failure(self, state: State, call: TaskCall) -> Failure | None:
        """The first precondition of ``call`` that does not hold in ``state``, or None."""
        call = self.check_call(call)
        rule = self.tasks[call.task]
        if call.task not in self.objects[call.args[0]].affords:
            return Failure(call, Condition("affords", (rule.params[0], call.task), "ol"), (call.args[0], call.task))
        binding = dict(zip(rule.params, call.args))
        for condition in rule.requires:
            if not self._holds(state, condition, binding):
                return Failure(call, condition, tuple(condition.bind(binding)))
        return None

    def feasible(self, state: State, call: TaskCall) -> bool:
        return self.failure(state, call) is None

    def available(self, state: State) -> tuple[TaskCall, ...]:
        """Every feasible task call, in world-file order of tasks and objects."""
        found: list[TaskCall] = []
        memo: dict[str, bool] = {}

        def reach(obj: str) -> bool:
            if obj not in memo:
                memo[obj] = reachable(state, self.objects, obj)
            return memo[obj]

        for task, (early, late, candidates) in self._compiled.items():
            for x in self._affording[task]:
                if not all(test(state, x, x, reach) for test in early):
                    continue
                if candidates is None:
                    found.append(TaskCall(task, (x,)))
                    continue
                for y in candidates:
                    if all(test(state, x, y, reach) for test in late):
                        found.append(TaskCall(task, (x, y)))
        return tuple(found)

    def apply(self, state: State, call: TaskCall | str) -> State:
        """The state after ``call``; raise NeemOracleError naming the failed precondition."""
        call = self.check_call(call)
        failure = self.failure(state, call)
        if failure is not None:
            raise NeemOracleError(str(failure))
        return self._effects(state, call)

    def replay(self, calls: Iterable[TaskCall | str], state: State | None = None) -> Iterator[tuple[State, TaskCall]]:
        """Yield (state before, call) for each call, applying it; infeasible calls raise."""
        state = self.initial_state() if state is None else state
        for call in calls:
            call = self.check_call(call)
            yield state, call
            state = self.apply(state, call)

    # --- repair -------------------------------------------------------------------------------
    def repair(self, state: State, call: TaskCall | str, park: str | None = None, depth: int = 4) -> list[TaskCall] | None:
        """The intermediate tasks plus ``call`` that make it feasible from ``state``, or None.

        The first failing precondition is fixed by one achieving task (itself repaired
        recursively), then the check repeats: a held object is put down on ``park`` (the world's
        park surface by default), a closed container is opened, an object to hold is picked.
        Conditions about the target's own state (already open, already on) are not repaired.
        """
        call = self.check_call(call)
        park = self.park if park is None else park
        plan: list[TaskCall] = []
        current = state
        for _ in range(8):
            failure = self.failure(current, call)
            if failure is None:
                return plan + [call]
            if depth == 0:
                return None
            fix = self._achiever(current, failure, park)
            if fix is None:
                return None
            steps = self.repair(current, fix, park, depth - 1)
            if steps is None:
                return None
            for step in steps:
                current = self._effects(current, step)
            plan.extend(steps)
        return None

    def _achiever(self, state: State, failure: Failure, park: str) -> TaskCall | None:
        name, bound = failure.condition.name, failure.bound
        if name == "hand_free":
            return TaskCall("place", (state.held, self._park_for(state, state.held, park)))  # type: ignore[arg-type]
        if name == "holding":
            return TaskCall("pick", (bound[0],))
        if name == "reachable":
            return self._unblock(state, bound[0], park)
        if name == "accepts":
            destination = bound[0]
            spec = self.objects[destination]
            if spec.kind == "container" and destination not in state.opened:
                return TaskCall("open", (destination,))
            if spec.kind == "appliance" and destination in state.switched_on:
                return TaskCall("turn_off", (destination,))
            if not reachable(state, self.objects, destination):
                return self._unblock(state, destination, park)
        return None

    def _unblock(self, state: State, obj: str, park: str) -> TaskCall | None:
        block = blocker(state, self.objects, obj)
        if block is None:
            return None
        if block == state.held:
            return TaskCall("place", (block, self._park_for(state, block, park)))
        spec = self.objects[block]
        if spec.kind == "container":
            return TaskCall("open", (block,))
        if spec.kind == "appliance":
            return TaskCall("turn_off", (block,))
        return None

    def _could_bind(self, rule: TaskRule, obj: str) -> bool:
        """Whether ``obj`` may fill the second parameter in some state (tags and kinds only)."""
        spec = self.objects[obj]
        second = rule.params[1]
        for condition in rule.requires:
            if condition.name == "tagged" and condition.args[0] == second and condition.args[1] not in spec.tags:
                return False
            if condition.name == "accepts" and condition.args[0] == second:
                if spec.kind not in ("surface", "container") and not spec.accepts:
                    return False
        return True

    def _compile(self, condition: Condition, params: tuple[str, ...]) -> Test:
        """A test ``f(state, first, second, reach)`` equivalent to ``_holds`` for this condition."""
        pick: list[Callable[[str, str], str]] = [(lambda x, y: x) if a == params[0] else (lambda x, y: y)
                                              for a in condition.args]
        name, args, objects = condition.name, condition.args, self.objects
        if name == "hand_free":
            return lambda s, x, y, r: s.held is None
        if name == "holding":
            p0 = pick[0]
            return lambda s, x, y, r: s.held == p0(x, y)
        if name == "reachable":
            p0 = pick[0]
            return lambda s, x, y, r: r(p0(x, y))
        if name == "tagged":
            p0, tag = pick[0], args[1]
            return lambda s, x, y, r: tag in objects[p0(x, y)].tags
        if name == "accepts":
            p0, p1 = pick
            return lambda s, x, y, r: self._accepts(s, p0(x, y), p1(x, y), r)
        binding_names = params
        return lambda s, x, y, r: self._holds(s, condition, dict(zip(binding_names, (x, y))))

    def _park_for(self, state: State, held: str, park: str) -> str:
        if self._accepts(state, park, held):
            return park
        return self.park

    # --- predicates and effects -----------------------------------------------------------------
    def _accepts(self, state: State, destination: str, obj: str, reach: Reach | None = None) -> bool:
        if destination == obj or destination == HAND:
            return False
        spec = self.objects[destination]
        if spec.kind == "item" and not spec.accepts:
            return False
        if not (reach(destination) if reach is not None else reachable(state, self.objects, destination)):
            return False
        if spec.kind == "surface":
            return True
        if spec.kind == "container":
            return destination in state.opened
        if spec.kind == "appliance" and destination in state.switched_on:
            return False
        return bool(spec.accepts & self.objects[obj].tags)

    def _holds(self, state: State, condition: Condition, binding: Mapping[str, str]) -> bool:
        name = condition.name
        args = condition.bind(binding)
        if name == "hand_free":
            return state.held is None
        if name == "holding":
            return state.held == args[0]
        if name == "reachable":
            return reachable(state, self.objects, args[0])
        if name == "tagged":
            return args[1] in self.objects[args[0]].tags
        if name == "opened":
            return args[0] in state.opened
        if name == "closed":
            return self.objects[args[0]].kind == "container" and args[0] not in state.opened
        if name == "switched_on":
            return args[0] in state.switched_on
        if name == "switched_off":
            return self.objects[args[0]].kind == "appliance" and args[0] not in state.switched_on
        if name == "accepts":
            return self._accepts(state, args[0], args[1])
        if name == "distinct":
            return args[0] != args[1]
        raise AssertionError(f"unvalidated predicate {name}")  # worldfile.load_world rejects unknown names

    def _effects(self, state: State, call: TaskCall) -> State:
        rule = self.tasks[call.task]
        binding = dict(zip(rule.params, call.args))
        for effect in rule.effects:
            args = effect.bind(binding)
            if effect.name == "grasp":
                state = state.grasp(args[0])
            elif effect.name == "put":
                state = state.put(args[0], args[1])
            elif effect.name == "open":
                state = state.open(args[0])
            elif effect.name == "close":
                state = state.close(args[0])
            elif effect.name == "switch_on":
                state = state.switch_on(args[0])
            elif effect.name == "switch_off":
                state = state.switch_off(args[0])
        return state
