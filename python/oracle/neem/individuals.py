"""The individuals of the NEEM a ``NeemLogger`` writes (oracle.neem.writer): their IRIs, the triples
each one gets the first time it is met, and the caches of what exists (stored or buffered), which
calls were checked and which plans are known, which must stay consistent with what is stored.

Objects and agents are shared by every event of the NEEM; every action executes its own task
individual with its own roles, which classify their objects only during the action; plans define
one shared task description per call (docs/store.md)."""

from __future__ import annotations

import os
import re
import time
from collections.abc import Sequence

from oracle.chains import TaskCall, modes_error, parse_call
from oracle.errors import ChainSyntaxError, LoggingError, OntologyError
from oracle.neem import terms as T
from oracle.neem.checks import check_call, check_performer
from oracle.neem.records import Target, TripleBuffer, fact_extent
from oracle.ontology.model import OdbOntology
from oracle.store import RDF_TYPE, Store
from oracle.store.model import INFINITY, USER_GRAPH
from oracle.timeline import Instant

_SLUG = re.compile(r"[^A-Za-z0-9_\-]+")


def slug(text: str) -> str:
    """``text`` as a piece of an IRI: letters, digits, ``_`` and ``-`` only."""
    return _SLUG.sub("-", text).strip("-") or "x"


def person_iri(ns: str, user: str) -> str:
    """The user's agent individual; never the robot's own, even for a user named "robot"."""
    name = slug(user)
    return f"{ns}Agent_{name}" if name != "robot" else f"{ns}Agent_user-robot"


class Individuals:
    """Mints the individuals of one NEEM being written into a call's triples, and knows which exist."""

    def __init__(self, store: Store, onto: OdbOntology, target: Target, *, user: str, clocked: bool) -> None:
        self.store = store
        self.onto = onto
        #: The NEEM written, where ``exists`` looks.
        self.target = target
        self.ns: str = onto.namespace
        self.vocab = onto.vocab
        self.user = user
        #: False for a NEEM on the sequence clock (oracle.timeline): its times are positions.
        self.clocked = clocked
        #: Individuals known to be stored (or buffered): no store query needed for them.
        self.known: set[str] = set()
        #: Whether ``known`` holds every subject the NEEM has that ``exists`` may be asked
        #: about (``know_all``): then it asks the store nothing.
        self.complete = False
        self._keys: dict[TaskCall, str] = {}
        #: Calls already checked, and plans of calls already in ``known``: an available set of
        #: 20 plans that were logged before costs 20 dictionary look-ups, not 20 checks.
        self.resolved: dict[TaskCall | str, TaskCall] = {}
        self.plans: dict[TaskCall, str] = {}
        #: Looked up once: objects' IRIs, calls' task class and role classes, parts of day.
        self._object_iris: dict[str, str] = {}
        self._task_classes: dict[TaskCall, tuple[str, tuple[str | None, ...]]] = {}
        self._parts: dict[str, str] = {}
        self._imagines = self.vocab.imagines_situation
        # Event ids in ObjectId's layout (seconds, 5 random bytes, counter), made without
        # ObjectId's per-call lock and pid check.
        self._random = os.urandom(5).hex()
        self._counter = int.from_bytes(os.urandom(3), "big") >> 1  # 8M ids before it wraps

    def event(self, kind: str) -> str:
        # ObjectId-like ids grow with time, so new IRIs land at the end of the indexes (few
        # dirty pages per commit) and stay unique across processes (random part per logger).
        self._counter = counter = (self._counter + 1) & 0xFFFFFF
        return f"{self.ns}{kind}_{int(time.time()):08x}{self._random}{counter:06x}"

    def named(self, cls_iri: str) -> str:
        """A fresh individual of a class, named as KnowRob's ``new_iri(I, Class)`` names it:
        the class IRI, ``_``, a unique id (openEASE labels a timeline's bars from that name)."""
        self._counter = counter = (self._counter + 1) & 0xFFFFFF
        return f"{cls_iri}_{int(time.time()):08x}{self._random}{counter:06x}"

    def task_named(self, cls_iri: str) -> str:
        """A fresh task individual of a task class: ``named`` with the class's local name in
        CamelCase (``odb:turn_on`` -> ``odb:TurnOn_<id>``), so the IRI holds exactly one ``_``
        (where the namespace holds none): openEASE's timeline rule splits a task individual
        with ``atomic_list_concat([Task, _], '_', TaskInstance)`` and drops it otherwise."""
        cut = max(cls_iri.rfind("#"), cls_iri.rfind("/")) + 1
        local = cls_iri[cut:]
        if "_" in local:
            local = "".join(word[:1].upper() + word[1:] for word in local.split("_"))
        return self.named(cls_iri[:cut] + local)

    def know_all(self) -> None:
        """Read every subject of the NEEM once (a new one: its TBox's, ~1,000) and answer
        ``exists`` from them and what this logger writes from now on: for a writer no other one
        writes beside, such as an import's into the NEEM it made, whose subject index is then
        left out until it ends (tables.DEFERRED)."""
        self.known.update(doc["s"] for doc in self.store.find(self.target.writing))
        self.complete = True

    def forget(self) -> None:
        """After a commit that failed: what ``known`` holds may name individuals never stored."""
        self.known.clear()
        self.complete = False

    def exists(self, iri: str) -> bool:
        if iri in self.known:
            return True
        if self.complete:
            return False
        if next(self.store.find(self.target.writing, s=iri, limit=1, exact=True), None) is not None:
            self.known.add(iri)
            return True
        return False

    def new(self, iri: str, out: TripleBuffer) -> bool:
        """True the first time an individual is met (then the caller writes its triples)."""
        if iri in out.created or self.exists(iri):
            return False
        out.created.add(iri)
        return True

    def individual(self, iri: str, cls_iri: str, out: TripleBuffer, since: float = 0.0) -> str:
        if self.new(iri, out):
            out.add(iri, RDF_TYPE, cls_iri, since)
            out.add(iri, RDF_TYPE, T.NAMED_INDIVIDUAL, since)
        return iri

    def object_iri(self, name: str) -> str:
        iri = self._object_iris.get(name)
        if iri is None:
            iri = f"{self.ns}Object_{slug(name)}"
            if len(self._object_iris) < 100_000:
                self._object_iris[name] = iri
        return iri

    def obj(self, name: str, out: TripleBuffer, since: float) -> str:
        """The object individual of an odb object, typed with its class the first time."""
        iri = self.object_iri(name)
        if iri in self.known:  # typed already: the class need not be looked up again
            return iri
        try:
            cls_iri = self.onto.object_iri(name)
        except OntologyError as error:
            raise LoggingError(str(error)) from None
        return self.individual(iri, cls_iri, out, since)

    def agent(self, who: str, out: TripleBuffer) -> str:
        if who == "robot":
            return self.individual(f"{self.ns}Agent_robot", T.ROBOT_CLASS, out)
        if who != "user":
            raise LoggingError(modes_error(who))
        return self.individual(person_iri(self.ns, self.user), T.PERSON_CLASS, out)

    def performers(self, action: str, task: str, who: str, begin: Instant, end: Instant, out: TripleBuffer) -> None:
        """``action`` performed by the robot, the user, or both (``together``). Together, each
        agent also plays a soma:AgentRole of the action's task during it, as neem-interface adds
        a participant with its role (``has_role(Agent, Role) during Action``, ``task_role``)."""
        check_performer(who)
        if who != "together":
            out.add(action, T.PERFORMED_BY, self.agent(who, out))
            return
        for agent in (self.agent("robot", out), self.agent("user", out)):
            out.add(action, T.PERFORMED_BY, agent)
            role = self.event("Role")
            out.add(role, RDF_TYPE, T.AGENT_ROLE)
            out.add(role, RDF_TYPE, T.NAMED_INDIVIDUAL)
            out.add(task, T.IS_TASK_OF, role)
            out.add(role, T.CLASSIFIES, agent, *fact_extent(begin.seconds, end.seconds))

    def resolve(self, call: TaskCall | str) -> TaskCall:
        resolved = self.resolved.get(call)
        if resolved is not None:
            return resolved
        original = call
        if isinstance(call, str):
            try:
                call = parse_call(call)
            except ChainSyntaxError as error:
                raise LoggingError(str(error)) from None
        check_call(self.onto, call)
        if len(self.resolved) < 100_000:
            self.resolved[original] = call
        return call

    def task(self, call: TaskCall, out: TripleBuffer, since: float) -> str:
        """The task a plan of a call defines, with its roles (``Role dul:classifies Object``):
        one description per call, shared by every imagining and preference that names it."""
        key = self._keys.get(call)
        if key is None:
            key = self._keys[call] = slug(str(call).replace(", ", "__").replace("(", "__").replace(")", ""))
        task = f"{self.ns}Task_{key}"
        if task in self.known or not self.new(task, out):
            return task
        roles = self.typed_task(task, call, out)
        for index, (arg, role_class) in enumerate(zip(call.args, roles)):
            obj = self.obj(arg, out, since)
            if role_class is None:
                continue
            role = f"{self.ns}Role_{key}__{index}"
            out.add(role, RDF_TYPE, role_class)
            out.add(role, RDF_TYPE, T.NAMED_INDIVIDUAL)
            out.add(task, T.IS_TASK_OF, role)
            # An imagined plan's role classifies its object at the instant the plan was first
            # imagined (or ranked), not always: ``has_role(O, R) during A`` then names only the
            # roles O played in the actions of that time (docs/store.md, "Plans").
            out.add(role, T.CLASSIFIES, obj, *fact_extent(since, since))
        return task

    def task_class(self, call: TaskCall) -> tuple[str, tuple[str | None, ...]]:
        """The call's task class and the SOMA role class of each argument."""
        known = self._task_classes.get(call)
        if known is None:
            try:
                known = (self.onto.task_iri(call.task), self.onto.task_roles(call.task, len(call.args)))
            except OntologyError as error:
                raise LoggingError(str(error)) from None
            if len(self._task_classes) < 100_000:
                self._task_classes[call] = known
        return known

    def typed_task(self, task: str, call: TaskCall, out: TripleBuffer) -> tuple[str | None, ...]:
        """Type ``task`` with the call's task class; the SOMA role class of each argument."""
        known = self.task_class(call)
        out.add(task, RDF_TYPE, known[0])
        out.add(task, RDF_TYPE, T.NAMED_INDIVIDUAL)
        return known[1]

    def executed_task(self, call: TaskCall, begin: Instant, end: Instant, out: TripleBuffer) -> str:
        """A fresh task individual for one action, with one role per argument; the role
        classifies its object during the action only (neem-interface's
        ``has_role(Obj, Role) during Action``), the task's type and roles hold always."""
        task = self.task_named(self.task_class(call)[0])
        roles = self.typed_task(task, call, out)
        for arg, role_class in zip(call.args, roles):
            if role_class is None:
                continue
            role = self.event("Role")
            out.add(role, RDF_TYPE, role_class)
            out.add(role, RDF_TYPE, T.NAMED_INDIVIDUAL)
            out.add(task, T.IS_TASK_OF, role)
            out.add(role, T.CLASSIFIES, self.object_iri(arg), *fact_extent(begin.seconds, end.seconds))
        return task

    def plan(self, call: TaskCall, out: TripleBuffer, since: float) -> str:
        plan = self.plans.get(call)
        if plan is not None:
            return plan
        key = self._keys.get(call)
        if key is not None and f"{self.ns}Plan_{key}" in self.known:
            plan = self.plans[call] = f"{self.ns}Plan_{key}"
            return plan
        task = self.task(call, out, since)
        plan = f"{self.ns}Plan_{task[len(self.ns) + len('Task_'):]}"
        if self.new(plan, out):
            out.add(plan, RDF_TYPE, T.PLAN)
            out.add(plan, RDF_TYPE, T.NAMED_INDIVIDUAL)
            out.add(plan, T.PLAN_FOR, task)
        return plan

    def interval(self, begin: Instant, end: Instant, out: TripleBuffer) -> str:
        """A dul:TimeInterval also typed with its odb:TimeOfDay part (that is how it is recorded;
        on the sequence clock there is none, and a clock time there is an error, as is a position
        in a NEEM with a clock)."""
        if (begin.part_of_day is None) == self.clocked:
            raise LoggingError(f"NEEM {self.target.neem_id!r} has a clock: a sequence position is no time" if self.clocked else
                               f"NEEM {self.target.neem_id!r} has no clock (logged from a time-less log): give positions, not times")
        interval = self.event("TimeInterval")
        out.add(interval, RDF_TYPE, T.TIME_INTERVAL)
        if begin.part_of_day is not None:
            part = self._parts.get(begin.part_of_day)
            if part is None:
                part = self._parts[begin.part_of_day] = self.vocab.part_of_day(begin.part_of_day)
            out.add(interval, RDF_TYPE, part)
        out.add(interval, T.BEGIN, begin.seconds)
        out.add(interval, T.END, end.seconds)
        return interval

    def mental(self, task_class: str, at: Instant, out: TripleBuffer, who: str = "robot") -> str:
        action = self.event("MentalAction")
        task = self.task_named(task_class)  # one task per action, mental ones too
        out.add(task, RDF_TYPE, task_class)
        out.add(task, RDF_TYPE, T.NAMED_INDIVIDUAL)
        out.add(action, RDF_TYPE, T.MENTAL_ACTION)
        out.add(action, T.EXECUTES, task)
        out.add(action, T.PERFORMED_BY, self.agent(who, out))
        out.add(action, T.HAS_INTERVAL, self.interval(at, at, out))
        return action

    def imagining(self, calls: Sequence[TaskCall], when: Instant, out: TripleBuffer,
                  known: list[str] | None = None) -> tuple[str, list[str]]:  # fmt: skip
        """The imagining of ``calls`` (or of the plans ``known``, all stored or buffered);
        returns it and the plans it imagines."""
        action = self.mental(T.IMAGINING, when, out)
        imagines = self._imagines
        if known is not None:
            out.extend([(action, imagines, plan, USER_GRAPH, 0.0, INFINITY) for plan in known])
            return action, known
        plans = self.plans
        chosen = []
        for call in calls:
            plan = plans.get(call)
            if plan is None:
                plan = self.plan(call, out, when.seconds)
            chosen.append(plan)
            out.append((action, imagines, plan, USER_GRAPH, 0.0, INFINITY))
        return action, chosen

    def state(self, action: str, state: str, out: TripleBuffer) -> None:
        region = T.EXECUTION_STATES[state]
        self.individual(region, T.EXECUTION_STATE_REGION, out)
        out.add(action, T.EXECUTION_STATE, region)

    def idle(self, begin: Instant, end: Instant, out: TripleBuffer) -> str:
        idle = self.event("Action")
        task = self.task_named(self.vocab.idle_task)
        out.add(task, RDF_TYPE, self.vocab.idle_task)
        out.add(task, RDF_TYPE, T.NAMED_INDIVIDUAL)
        out.add(idle, RDF_TYPE, T.ACTION)
        out.add(idle, RDF_TYPE, T.NAMED_INDIVIDUAL)
        out.add(idle, T.EXECUTES, task)
        out.add(idle, T.PERFORMED_BY, self.agent("robot", out))
        out.add(idle, T.HAS_INTERVAL, self.interval(begin, end, out))
        return idle
