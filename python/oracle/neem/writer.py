"""Writing a NEEM (thesis 3.4-3.5): what the robot perceived, could do, did and predicted, as triples.

Why this module is large: it has one job, turning the robot's calls into one NEEM's triples, and
its parts (the individuals it mints, the calls it has checked, the plans it knows, the buffer it
commits, the clock it keeps) share caches that must stay consistent with what is stored; split,
they would share private state. Reading back lives in ``neem.query``, persisting and wiping in
``neem.lifecycle``, bulk import in ``neem.importing``.

One NEEM per user. Every public call validates first and then writes one transaction, so bad
input raises before anything is written and a killed process loses at most the call in flight.
Every action executes its own task individual with its own roles, as neem-interface writes them,
and the roles classify their objects only during the action (``has_role(O, R) during A``). Plans
(what an imagining found available, what a preference ranked) define one shared task description
per call. Objects and agents are shared by every event of the NEEM. See docs/store.md.
"""

from __future__ import annotations

import math
import os
import re
import time
import uuid
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any
from datetime import datetime, timezone

from oracle.chains import MODES, TaskCall, modes_error, parse_call
from oracle.errors import ChainSyntaxError, LoggingError, OntologyError, StoreError
from oracle.neem import terms as T
from oracle.neem.lifecycle import wipe_temporary_neems
from oracle.neem.query import summarize_neem, summary_after
from oracle.neem.tf import Pose, frame_name, tf_document
from oracle.ontology.model import OdbOntology
from oracle.ontology.provenance import META_KEY as ONTOLOGY_KEY, check_logged_with, record_of
from oracle.store import RDF_TYPE, Store, TriplePattern, Var
from oracle.store.base import SUMMARY_KEY
from oracle.store.model import INFINITY, USER_GRAPH, TripleRow, Value
from oracle.store.ids import ALIAS_KEY, alias_of, check_alias, find_neem, is_object_id, new_neem_id, unique_alias
from oracle.timeline import IDLE_THRESHOLD_S, Instant, Moment, TimeValueError, has_clock, is_idle_gap, sequence_instant

if TYPE_CHECKING:
    from oracle.store.tbox import TBox  # rdflib: only a NEEM's creation loads it (create)

_SLUG = re.compile(r"[^A-Za-z0-9_\-]+")
#: NEEM ids are collection prefixes: no underscores (see store.base.check_neem_id).
_NEEM_SLUG = re.compile(r"[^A-Za-z0-9\-]+")


def _instant(moment: Moment) -> Instant:
    try:
        return Instant.of(moment)
    except TimeValueError as error:
        raise LoggingError(str(error)) from None


@dataclass(frozen=True)
class _Episode:
    """The recording session being written: its soma:Episode, the top-level action it is the
    setting for (whose constituents the logged actions are), that action's interval and the
    latest end logged in it (the interval's end, written when the session closes)."""

    key: str
    iri: str
    top: str
    interval: str
    end: float
    #: The session's actions, written as the top-level action's constituents when it closes.
    members: tuple[str, ...] = ()


@dataclass(frozen=True)
class LoggedAction:
    """What ``NeemLogger.action`` wrote: the action, and the idle action it inserted before it."""

    iri: str
    call: TaskCall
    begin: float
    end: float
    part_of_day: str | None
    task: str
    idle: str | None = None
    imagining: str | None = None


class _Out(list[TripleRow]):
    """Triples of one call, before they are written, and the individuals they create.

    They are plain ``(s, p, o, graph, since, until)`` tuples, as ``Store.insert`` takes them: a
    call writes ~50, and a tuple costs a third of a ``Triple`` to make."""

    def __init__(self) -> None:
        super().__init__()
        self.created: set[str] = set()

    def add(self, s: str, p: str, o: Value, since: float = 0.0, until: float = INFINITY) -> None:
        self.append((s, p, o, USER_GRAPH, since, until))


def fact_extent(begin: float, end: float) -> tuple[float, float]:
    """The scope of a fact that holds during an action from ``begin`` to ``end``. KnowRob sees a
    fact only where its scope has an extent (since < until, ``kb_scope``), so an instantaneous
    action (logged with a start only) scopes its facts to the shortest interval a double holds,
    ``[begin, nextafter(begin)]``: ``has_role(O, R) during A`` then answers as it does for any
    action, and the extent ends before any later action starts (docs/store.md)."""
    return (begin, end) if end > begin else (begin, math.nextafter(begin, math.inf))


def check_state(state: object) -> None:
    """LoggingError unless ``state`` is None or an execution state KnowRob names."""
    if state is not None and state not in T.EXECUTION_STATES:
        raise LoggingError(f"state must be one of {', '.join(T.EXECUTION_STATES)}, got {state!r}")


def _slug(text: str) -> str:
    return _SLUG.sub("-", text).strip("-") or "x"


def person_iri(ns: str, user: str) -> str:
    """The user's agent individual; never the robot's own, even for a user named "robot"."""
    slug = _slug(user)
    return f"{ns}Agent_{slug}" if slug != "robot" else f"{ns}Agent_user-robot"


#: Who may perform an action: the robot, the user it assists, or both together (chains.MODES).
PERFORMERS = MODES


def check_performer(who: object) -> str:
    """``who`` if it names a performer (PERFORMERS), else LoggingError."""
    if who not in PERFORMERS:
        raise LoggingError(modes_error(who))
    return str(who)


def check_call(onto: OdbOntology, call: TaskCall) -> None:
    """LoggingError unless the call's task and objects are in the ontology and its objects fit
    the task's roles (the checks an action gets before anything is written)."""
    if call.task not in onto.tasks:
        raise LoggingError(f"unknown task {call.task!r} in {call}; known tasks: {', '.join(sorted(onto.tasks))}")
    for arg in call.args:
        if arg not in onto.objects:
            raise LoggingError(f"unknown object {arg!r} in {call}")
    try:
        onto.task_roles(call.task, len(call.args))
    except OntologyError as error:
        raise LoggingError(str(error)) from None


def _place(store: Store, user: str, name: str | None, replace: bool) -> tuple[str, str | None]:
    """The id and alias of a NEEM ``create`` makes: ``name`` (an id or alias) or the user's name
    when None; a name of a NEEM that exists means that NEEM, only with ``replace``."""
    try:
        if name is None:
            base = _NEEM_SLUG.sub("-", user).strip("-")[:48] or "user"
            existing = find_neem(store, base) if replace else None
            if existing is not None:
                return existing.id, alias_of(existing)
            return new_neem_id(), unique_alias(store, base)
        existing = find_neem(store, name)
        if existing is not None:
            if not replace:
                raise LoggingError(f"NEEM {name!r} already exists (replace it, or choose another name)")
            return existing.id, alias_of(existing)
        return (name, None) if is_object_id(name) else (new_neem_id(), check_alias(name))
    except StoreError as error:
        raise LoggingError(str(error)) from None


class NeemLogger:
    """Writes one user's episode into one NEEM of a store."""

    def __init__(
        self,
        store: Store,
        onto: OdbOntology,
        neem_id: str,
        *,
        idle_threshold: float = IDLE_THRESHOLD_S,
        commit_every: int = 1,
    ) -> None:
        """``commit_every`` > 1 groups that many calls into one transaction (much faster on slow
        disks); only calls counted in ``committed`` are then guaranteed to survive a crash."""
        if commit_every < 1:
            raise LoggingError(f"commit_every must be at least 1, got {commit_every}")
        self.store = store
        self.commit_every = commit_every
        #: How many calls (actions, perceptions, ...) are durably in the store.
        self.committed = 0
        self._buffer: list[TripleRow] = []
        self._tf: list[dict[str, Any]] = []  # transforms of perceptions, written with the triples
        self._tf_seq = 0
        self._buffered_calls = 0
        self.onto = onto
        #: The NEEM the writes go to: a hidden staging NEEM until ``close()`` when it replaces one.
        self._writing = neem_id
        self.idle_threshold = idle_threshold
        self.ns: str = onto.namespace
        self.vocab = onto.vocab
        info = store.neem(neem_id)
        check_logged_with(neem_id, info.meta, onto)
        #: False for a NEEM on the sequence clock (oracle.timeline): its times are positions.
        self.clocked = has_clock(info.meta)
        self.user: str = info.user or "user"
        #: Individuals known to be stored (or buffered): no store query needed for them.
        self._known: set[str] = set()
        self._keys: dict[TaskCall, str] = {}
        #: Calls already checked, and plans of calls already in ``_known``: an available set of
        #: 20 plans that were logged before costs 20 dictionary look-ups, not 20 checks.
        self._resolved: dict[TaskCall | str, TaskCall] = {}
        self._plans: dict[TaskCall, str] = {}
        #: Looked up once: objects' IRIs, calls' task class and role classes, parts of day.
        self._object_iris: dict[str, str] = {}
        self._task_classes: dict[TaskCall, tuple[str, tuple[str | None, ...]]] = {}
        self._parts: dict[str, str] = {}
        #: The plans of an available set logged before, by the identity of its tuple, which is
        #: kept here so that no other object has that id meanwhile: the rows of a chains file
        #: share one tuple per distinct set (oracle.chains), a persona meets a few hundred.
        self._sets: dict[int, tuple[object, list[str]]] = {}
        self._imagines = self.vocab.imagines_situation
        # Event ids in ObjectId's layout (seconds, 5 random bytes, counter), made without
        # ObjectId's per-call lock and pid check.
        self._random = os.urandom(5).hex()
        self._counter = int.from_bytes(os.urandom(3), "big") >> 1  # 8M ids before it wraps
        #: Latest begin and latest end of the executed actions: actions may overlap, as events
        #: do in KnowRob (two sensors firing at once), but none may start before the one before.
        #: Read from the NEEM when something timed is first logged (``_check_time``): writing
        #: a ranking back (``preference``, stamped with its decision's time) needs neither.
        self._last_begin: Instant | None = None
        self._last_end: Instant | None = None
        self._clock_resumed = False
        #: The open recording session (None before the first action of this logger's run).
        self._episode: _Episode | None = None
        #: What ``neems`` lists, as committed; moved on with every commit (oracle.neem.query).
        known = summarize_neem(store, neem_id, info)
        self._summary = {"actions": known.actions, "begin": known.begin, "end": known.end}
        #: The NEEM this one replaces when ``close()`` swaps it in (``create(replace=True)``).
        self._replaces: str | None = None
        self._may_replace = False

    # -- creation ---------------------------------------------------------------------------
    @classmethod
    def create(
        cls,
        store: Store,
        onto: OdbOntology,
        *,
        user: str,
        neem_id: str | None = None,
        temporary: bool = False,
        replace: bool = False,
        tbox: TBox | None = None,
        idle_threshold: float = IDLE_THRESHOLD_S,
        commit_every: int = 1,
        hidden: bool = False,
        meta: dict[str, object] | None = None,
    ) -> NeemLogger:
        """A new NEEM for ``user`` holding the ontology's TBox: its id a fresh ObjectId, its alias
        ``neem_id`` or the user's name made unique (an existing NEEM of that name or id is an
        error, or with ``replace`` the NEEM replaced, which keeps its id and alias).

        With ``replace`` (of an existing NEEM) or ``hidden`` the NEEM stays out of listings until
        ``close()``: the old one is untouched until then, and a concurrent session start does
        not wipe a temporary NEEM still being imported."""
        if not isinstance(user, str) or not user.strip():
            raise LoggingError("a NEEM needs a user name")
        if commit_every < 1:
            raise LoggingError(f"commit_every must be at least 1, got {commit_every}")
        neem_id, alias = _place(store, user, neem_id, replace)
        recorded = record_of(onto)  # readers use the same ontology by default
        extra = {**(meta or {}), "name": alias or neem_id, ALIAS_KEY: alias}
        if recorded is not None:
            extra[ONTOLOGY_KEY] = recorded.to_meta()
        # The NEEM is built hidden and made visible with its TBox in one step: a NEEM without its
        # TBox (wrong closures) is never listed, even if the process is killed meanwhile. When it
        # replaces one, it stays hidden until ``close()``: the old NEEM is untouched until then.
        # An imagining's ~20 plans are half of what an action writes: the store may keep them
        # apart with fewer indexes (SQLite's side table, docs/store.md).
        created = store.create_staging(neem_id, user=user, meta={**extra, "temporary": temporary},
                                       side_property=onto.vocab.imagines_situation)  # fmt: skip
        staging: str | None = created
        try:
            from oracle.store.ontology_tbox import tbox_for
            from oracle.store.tbox import load_tbox

            load_tbox(store, created, tbox if tbox is not None else tbox_for(onto))
            if not hidden and not (replace and store.has_neem(neem_id)):
                store.swap_in(created, neem_id, replace=False)
                staging = None
            logger = cls(store, onto, staging or neem_id, idle_threshold=idle_threshold, commit_every=commit_every)
        except BaseException:
            if staging is not None:
                store.drop_neem(staging)
            raise
        if staging is not None:
            logger._replaces, logger._may_replace = neem_id, replace
        return logger

    @classmethod
    def start_session(
        cls, store: Store, onto: OdbOntology, *, user: str, tbox: TBox | None = None, idle_threshold: float = IDLE_THRESHOLD_S
    ) -> NeemLogger:
        """Privacy (thesis 3.5): wipe every temporary NEEM, then log into a fresh temporary one."""
        wipe_temporary_neems(store)
        stamp = datetime.now(timezone.utc).strftime("%Y%m%dT%H%M%S")
        neem_id = f"session-{stamp}-{uuid.uuid4().hex[:6]}"
        return cls.create(store, onto, user=user, neem_id=neem_id, temporary=True, tbox=tbox,
                          idle_threshold=idle_threshold)  # fmt: skip

    # -- individuals ------------------------------------------------------------------------
    def _event(self, kind: str) -> str:
        # ObjectId-like ids grow with time, so new IRIs land at the end of the indexes (few
        # dirty pages per commit) and stay unique across processes (random part per logger).
        self._counter = counter = (self._counter + 1) & 0xFFFFFF
        return f"{self.ns}{kind}_{int(time.time()):08x}{self._random}{counter:06x}"

    def _named(self, cls_iri: str) -> str:
        """A fresh individual of a class, named as KnowRob's ``new_iri(I, Class)`` names it:
        the class IRI, ``_``, a unique id (openEASE labels a timeline's bars from that name)."""
        self._counter = counter = (self._counter + 1) & 0xFFFFFF
        return f"{cls_iri}_{int(time.time()):08x}{self._random}{counter:06x}"

    def _exists(self, iri: str) -> bool:
        if iri in self._known:
            return True
        if next(self.store.find(self._writing, s=iri, limit=1, exact=True), None) is not None:
            self._known.add(iri)
            return True
        return False

    def _new(self, iri: str, out: _Out) -> bool:
        """True the first time an individual is met (then the caller writes its triples)."""
        if iri in out.created or self._exists(iri):
            return False
        out.created.add(iri)
        return True

    def _individual(self, iri: str, cls_iri: str, out: _Out, since: float = 0.0) -> str:
        if self._new(iri, out):
            out.add(iri, RDF_TYPE, cls_iri, since)
            out.add(iri, RDF_TYPE, T.NAMED_INDIVIDUAL, since)
        return iri

    def object_iri(self, name: str) -> str:
        iri = self._object_iris.get(name)
        if iri is None:
            iri = f"{self.ns}Object_{_slug(name)}"
            if len(self._object_iris) < 100_000:
                self._object_iris[name] = iri
        return iri

    def _object(self, name: str, out: _Out, since: float) -> str:
        iri = self.object_iri(name)
        if iri in self._known:  # typed already: the class need not be looked up again
            return iri
        try:
            cls_iri = self.onto.object_iri(name)
        except OntologyError as error:
            raise LoggingError(str(error)) from None
        return self._individual(iri, cls_iri, out, since)

    def _agent(self, who: str, out: _Out) -> str:
        if who == "robot":
            return self._individual(f"{self.ns}Agent_robot", T.ROBOT_CLASS, out)
        if who != "user":
            raise LoggingError(modes_error(who))
        return self._individual(person_iri(self.ns, self.user), T.PERSON_CLASS, out)

    def _performers(self, action: str, task: str, who: str, begin: Instant, end: Instant, out: _Out) -> None:
        """``action`` performed by the robot, the user, or both (``together``). Together, each
        agent also plays a soma:AgentRole of the action's task during it, as neem-interface adds
        a participant with its role (``has_role(Agent, Role) during Action``, ``task_role``)."""
        check_performer(who)
        if who != "together":
            out.add(action, T.PERFORMED_BY, self._agent(who, out))
            return
        for agent in (self._agent("robot", out), self._agent("user", out)):
            out.add(action, T.PERFORMED_BY, agent)
            role = self._event("Role")
            out.add(role, RDF_TYPE, T.AGENT_ROLE)
            out.add(role, RDF_TYPE, T.NAMED_INDIVIDUAL)
            out.add(task, T.IS_TASK_OF, role)
            out.add(role, T.CLASSIFIES, agent, *fact_extent(begin.seconds, end.seconds))

    def _resolve(self, call: TaskCall | str) -> TaskCall:
        resolved = self._resolved.get(call)
        if resolved is not None:
            return resolved
        original = call
        if isinstance(call, str):
            try:
                call = parse_call(call)
            except ChainSyntaxError as error:
                raise LoggingError(str(error)) from None
        check_call(self.onto, call)
        if len(self._resolved) < 100_000:
            self._resolved[original] = call
        return call

    def _task(self, call: TaskCall, out: _Out, since: float) -> str:
        """The task a plan of a call defines, with its roles (``Role dul:classifies Object``):
        one description per call, shared by every imagining and preference that names it."""
        key = self._keys.get(call)
        if key is None:
            key = self._keys[call] = _slug(str(call).replace(", ", "__").replace("(", "__").replace(")", ""))
        task = f"{self.ns}Task_{key}"
        if task in self._known or not self._new(task, out):
            return task
        roles = self._typed_task(task, call, out)
        for index, (arg, role_class) in enumerate(zip(call.args, roles)):
            obj = self._object(arg, out, since)
            if role_class is None:
                continue
            role = f"{self.ns}Role_{key}__{index}"
            out.add(role, RDF_TYPE, role_class)
            out.add(role, RDF_TYPE, T.NAMED_INDIVIDUAL)
            out.add(task, T.IS_TASK_OF, role)
            out.add(role, T.CLASSIFIES, obj)
        return task

    def _task_class(self, call: TaskCall) -> tuple[str, tuple[str | None, ...]]:
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

    def _typed_task(self, task: str, call: TaskCall, out: _Out) -> tuple[str | None, ...]:
        """Type ``task`` with the call's task class; the SOMA role class of each argument."""
        known = self._task_class(call)
        out.add(task, RDF_TYPE, known[0])
        out.add(task, RDF_TYPE, T.NAMED_INDIVIDUAL)
        return known[1]

    def _executed_task(self, call: TaskCall, begin: Instant, end: Instant, out: _Out) -> str:
        """A fresh task individual for one action, with one role per argument; the role
        classifies its object during the action only (neem-interface's
        ``has_role(Obj, Role) during Action``), the task's type and roles hold always."""
        task = self._named(self._task_class(call)[0])
        roles = self._typed_task(task, call, out)
        for arg, role_class in zip(call.args, roles):
            if role_class is None:
                continue
            role = self._event("Role")
            out.add(role, RDF_TYPE, role_class)
            out.add(role, RDF_TYPE, T.NAMED_INDIVIDUAL)
            out.add(task, T.IS_TASK_OF, role)
            out.add(role, T.CLASSIFIES, self.object_iri(arg), *fact_extent(begin.seconds, end.seconds))
        return task

    def _plan(self, call: TaskCall, out: _Out, since: float) -> str:
        plan = self._plans.get(call)
        if plan is not None:
            return plan
        key = self._keys.get(call)
        if key is not None and f"{self.ns}Plan_{key}" in self._known:
            plan = self._plans[call] = f"{self.ns}Plan_{key}"
            return plan
        task = self._task(call, out, since)
        plan = f"{self.ns}Plan_{task[len(self.ns) + len('Task_'):]}"
        if self._new(plan, out):
            out.add(plan, RDF_TYPE, T.PLAN)
            out.add(plan, RDF_TYPE, T.NAMED_INDIVIDUAL)
            out.add(plan, T.PLAN_FOR, task)
        return plan

    def _interval(self, begin: Instant, end: Instant, out: _Out) -> str:
        """A dul:TimeInterval also typed with its odb:TimeOfDay part (that is how it is recorded;
        on the sequence clock there is none, and a clock time there is an error, as is a position
        in a NEEM with a clock)."""
        if (begin.part_of_day is None) == self.clocked:
            raise LoggingError(f"NEEM {self._public_id} has a clock: a sequence position is no time" if self.clocked else
                               f"NEEM {self._public_id} has no clock (logged from a time-less log): give positions, not times")
        interval = self._event("TimeInterval")
        out.add(interval, RDF_TYPE, T.TIME_INTERVAL)
        if begin.part_of_day is not None:
            part = self._parts.get(begin.part_of_day)
            if part is None:
                part = self._parts[begin.part_of_day] = self.vocab.part_of_day(begin.part_of_day)
            out.add(interval, RDF_TYPE, part)
        out.add(interval, T.BEGIN, begin.seconds)
        out.add(interval, T.END, end.seconds)
        return interval

    def _mental(self, task_class: str, at: Instant, out: _Out, who: str = "robot") -> str:
        action = self._event("MentalAction")
        task = self._named(task_class)  # one task per action, mental ones too
        out.add(task, RDF_TYPE, task_class)
        out.add(task, RDF_TYPE, T.NAMED_INDIVIDUAL)
        out.add(action, RDF_TYPE, T.MENTAL_ACTION)
        out.add(action, T.EXECUTES, task)
        out.add(action, T.PERFORMED_BY, self._agent(who, out))
        out.add(action, T.HAS_INTERVAL, self._interval(at, at, out))
        return action

    # -- checks -----------------------------------------------------------------------------
    def _check_time(self, at: Instant, what: str) -> None:
        if not self._clock_resumed:
            self._last_begin, self._last_end = self._resume_clock()
            self._clock_resumed = True
        if self._last_begin is not None and at.seconds < self._last_begin.seconds:
            raise LoggingError(
                f"time goes backwards: {what} at {at.seconds:.3f} is before the start of the last action"
                f" ({self._last_begin.seconds:.3f}) in NEEM {self._public_id}"
            )

    def _resume_clock(self) -> tuple[Instant | None, Instant | None]:
        """When logging continues into an existing NEEM: the latest begin and end of its actions."""
        executed = {doc["s"] for doc in self.store.find(self._writing, p=RDF_TYPE, o=T.ACTION, exact=True)}
        if not executed:
            return None, None
        begins: list[float] = []
        ends: list[float] = []
        for row in self.store.match(
            self._writing,
            [TriplePattern(Var("A"), T.HAS_INTERVAL, Var("I")), TriplePattern(Var("I"), T.BEGIN, Var("B")),
             TriplePattern(Var("I"), T.END, Var("E"))],
        ):  # fmt: skip
            if row["A"] in executed:
                begins.append(row["B"])
                ends.append(row["E"])
        if not begins:
            return None, None
        if not self.clocked:
            return sequence_instant(max(begins)), sequence_instant(max(ends))
        return _instant(max(begins)), _instant(max(ends))

    # -- public API -------------------------------------------------------------------------
    def perceive(self, obj: str, at: Moment, pose: Pose | None = None) -> str:
        """The robot perceives an odb object; its type triple is scoped from the first perception.
        With a ``pose`` (thesis future work: raw technical data) the object's transform at that
        moment goes into the NEEM's tf collection, frame = the object IRI's local name."""
        when = _instant(at)
        self._check_time(when, f"perception of {obj!r}")
        if pose is not None and not isinstance(pose, Pose):
            raise LoggingError(f"perception of {obj!r}: pose must be a Pose, got {type(pose).__name__}")
        out = _Out()
        iri = self._object(obj, out, when.seconds)
        if pose is not None:
            self._tf_seq += 1
            self._tf.append(tf_document(frame_name(iri), pose, when.seconds, self._tf_seq))
        self._write(out)
        return iri

    def available(self, calls: Iterable[TaskCall | str], at: Moment) -> str:
        """The tasks available at a moment: a MentalAction executing Imagining that
        odb:imagines_situation one ActionExecutionPlan per task (thesis 3.4)."""
        when = _instant(at)
        resolved = [self._resolve(call) for call in calls]
        self._check_time(when, "available tasks")
        out = _Out()
        action, _ = self._imagining(resolved, when, out)
        self._write(out)
        return action

    def _imagining(self, calls: Sequence[TaskCall], when: Instant, out: _Out,
                   known: list[str] | None = None) -> tuple[str, list[str]]:  # fmt: skip
        """The imagining of ``calls`` (or of the plans ``known``, all stored or buffered);
        returns it and the plans it imagines."""
        action = self._mental(T.IMAGINING, when, out)
        imagines = self._imagines
        if known is not None:
            out.extend([(action, imagines, plan, USER_GRAPH, 0.0, INFINITY) for plan in known])
            return action, known
        plans = self._plans
        chosen = []
        for call in calls:
            plan = plans.get(call)
            if plan is None:
                plan = self._plan(call, out, when.seconds)
            chosen.append(plan)
            out.append((action, imagines, plan, USER_GRAPH, 0.0, INFINITY))
        return action, chosen

    def action(
        self,
        call: TaskCall | str,
        begin: Moment,
        end: Moment | None = None,
        *,
        performed_by: str = "robot",
        action_id: str | None = None,
        available: Iterable[TaskCall | str] | None = None,
        state: str | None = None,
        session: str | None = None,
    ) -> LoggedAction:
        """Log an executed action (and, in the same transaction, the tasks available when it
        started and the idle action filling a gap of ``idle_threshold`` seconds or more).

        ``state`` is what the robot reports of it (``succeeded``, ``failed``, ``cancelled``, ...:
        ``soma:hasExecutionState``, KnowRob's action_succeeded/1 and kin); None writes none.
        ``session`` names the recording session (one soma:Episode each); None: the UTC day of
        ``begin`` (one session per time-less log)."""
        call = self._resolve(call)
        check_state(state)
        check_performer(performed_by)
        if session is not None and (not isinstance(session, str) or not session.strip()):
            raise LoggingError(f"session must be a non-empty string, got {session!r}")
        start = _instant(begin)
        stop = start if end is None else _instant(end)
        if stop.seconds < start.seconds:
            raise LoggingError(f"{call}: ends ({stop.seconds:.3f}) before it starts ({start.seconds:.3f})")
        self._check_time(start, f"action {call}")
        options: list[TaskCall] = []
        entry = self._sets.get(id(available)) if available is not None else None
        known_plans = entry[1] if entry is not None and entry[0] is available else None
        if available is not None and known_plans is None:
            known = self._resolved.get  # most options were checked before: skip the call
            options = [known(c) or self._resolve(c) for c in available]
        if action_id is not None:
            iri = f"{self.ns}Action_{_slug(action_id)}"
            if self._exists(iri):  # stored or buffered (``_known``): whatever ``commit_every``
                raise LoggingError(f"duplicate action id {action_id!r} in NEEM {self._public_id}")
        else:
            iri = self._event("Action")
        out = _Out()
        if action_id is not None:
            out.created.add(iri)
        idle = None
        if self._last_end is not None and is_idle_gap(self._last_end.seconds, start.seconds, self.idle_threshold):
            idle = self._idle(self._last_end, start, out)
        imagining, plans = self._imagining(options, start, out, known_plans) if available is not None else (None, [])
        for arg in call.args:  # objects first: an unknown one raises before the task is built
            out.add(iri, T.PARTICIPANT, self._object(arg, out, start.seconds))
        task = self._executed_task(call, start, stop, out)
        out.add(iri, RDF_TYPE, T.ACTION)
        out.add(iri, RDF_TYPE, T.NAMED_INDIVIDUAL)
        out.add(iri, T.EXECUTES, task)
        self._performers(iri, task, performed_by, start, stop, out)
        out.add(iri, T.HAS_INTERVAL, self._interval(start, stop, out))
        if state is not None:
            self._state(iri, state, out)
        if idle is not None:  # the gap before an action is part of its session
            self._constituent(idle, start, start, session, out, begin=self._last_end)
        self._constituent(iri, start, stop, session, out)
        self._write(out)
        if known_plans is None and type(available) is tuple:  # immutable: the same set next time
            if len(self._sets) >= 4096:
                self._sets.clear()
            self._sets[id(available)] = (available, plans)
        self._last_begin = start
        if self._last_end is None or stop.seconds > self._last_end.seconds:
            self._last_end = stop
        return LoggedAction(iri, call, start.seconds, stop.seconds, start.part_of_day, task, idle, imagining)

    def _state(self, action: str, state: str, out: _Out) -> None:
        region = T.EXECUTION_STATES[state]
        self._individual(region, T.EXECUTION_STATE_REGION, out)
        out.add(action, T.EXECUTION_STATE, region)

    def _constituent(self, action: str, start: Instant, stop: Instant, session: str | None, out: _Out,
                     begin: Instant | None = None) -> None:  # fmt: skip
        """``action`` (which starts at ``begin``, default ``start``) a constituent of the session
        of ``start``; a session of another key (a new day, another name) first closes the open
        one and opens its own."""
        if session is not None:
            key = session
        elif not self.clocked:
            key = "sequence"
        else:
            key = datetime.fromtimestamp(start.seconds, timezone.utc).date().isoformat()
        episode = self._episode
        if episode is not None and episode.key != key:
            self._end_episode(out)
            episode = None
        if episode is None:
            episode = self._open_episode(key, start if begin is None else begin, out)
        self._episode = _Episode(episode.key, episode.iri, episode.top, episode.interval, max(episode.end, stop.seconds),
                                 (*episode.members, action))  # fmt: skip

    def _open_episode(self, key: str, start: Instant, out: _Out) -> _Episode:
        """neem-interface's ``mem_episode_start``: an episode that is the setting for a top-level
        action executing a physical task, performed by the robot, which plays an agent role."""
        episode, top, task, role = (self._named(c) for c in (T.EPISODE, T.PHYSICAL_ACTION, T.PHYSICAL_TASK, T.AGENT_ROLE))
        interval = self._event("TimeInterval")
        robot = self._agent("robot", out)
        for iri, cls_iri in ((episode, T.EPISODE), (top, T.PHYSICAL_ACTION), (task, T.PHYSICAL_TASK), (role, T.AGENT_ROLE)):
            out.add(iri, RDF_TYPE, cls_iri)
            out.add(iri, RDF_TYPE, T.NAMED_INDIVIDUAL)
        out.add(interval, RDF_TYPE, T.TIME_INTERVAL)  # typed as the actions' intervals are
        out.add(episode, T.INCLUDES_ACTION, top)
        out.add(top, T.EXECUTES, task)
        out.add(top, T.PERFORMED_BY, robot)
        out.add(task, T.IS_TASK_OF, role)
        out.add(role, T.CLASSIFIES, robot)
        out.add(top, T.HAS_INTERVAL, interval)
        out.add(interval, T.BEGIN, start.seconds)
        return _Episode(key, episode, top, interval, start.seconds)

    def _end_episode(self, out: _Out) -> None:
        """neem-interface's ``mem_episode_stop``: the session's actions become constituents of its
        top-level action, whose interval ends with the latest end logged in the session.

        Written together when the session closes, not one by one: a triple whose subject is an
        earlier individual (the top-level action) would make every later history read whole
        (oracle.historycache keeps a history only while every added subject is new)."""
        episode = self._episode
        if episode is not None:
            out.extend([(episode.top, T.HAS_CONSTITUENT, member, USER_GRAPH, 0.0, INFINITY) for member in episode.members])
            out.add(episode.interval, T.END, episode.end)
            self._episode = None

    def _idle(self, begin: Instant, end: Instant, out: _Out) -> str:
        idle = self._event("Action")
        task = self._named(self.vocab.idle_task)
        out.add(task, RDF_TYPE, self.vocab.idle_task)
        out.add(task, RDF_TYPE, T.NAMED_INDIVIDUAL)
        out.add(idle, RDF_TYPE, T.ACTION)
        out.add(idle, RDF_TYPE, T.NAMED_INDIVIDUAL)
        out.add(idle, T.EXECUTES, task)
        out.add(idle, T.PERFORMED_BY, self._agent("robot", out))
        out.add(idle, T.HAS_INTERVAL, self._interval(begin, end, out))
        return idle

    def preference(self, ranking: Sequence[tuple[TaskCall | str, float]], at: Moment) -> str:
        """A predicted preference (written by the oracle): a MentalAction executing Reasoning
        that odb:imagines_preference a PreferenceOrder (also typed soma:Order) which soma:orders
        one OrderedElement per task, each soma:encapsulates the task's plan and carries
        odb:hasPreferenceRank (1 = most preferred, the order given) and odb:hasPreferenceScore.
        Returns the PreferenceOrder's IRI.

        ``at`` is the time of the decision ranked; it may lie before actions already logged (a
        recorded NEEM ranked afterwards), so it is not checked against the last action's end and
        does not move the logger's clock."""
        when = _instant(at)
        resolved = [(self._resolve(call), float(score)) for call, score in ranking]
        out = _Out()
        action = self._mental(T.REASONING, when, out)
        order = self._event("PreferenceOrder")
        out.add(action, self.vocab.imagines_preference, order)
        out.add(order, RDF_TYPE, T.PREFERENCE_ORDER)
        out.add(order, RDF_TYPE, T.ORDER)
        for rank, (call, score) in enumerate(resolved, start=1):
            element = f"{order}_{rank}"
            out.add(element, RDF_TYPE, T.ORDERED_ELEMENT)
            out.add(order, T.ORDERS, element)
            out.add(element, T.ENCAPSULATES, self._plan(call, out, when.seconds))
            out.add(element, self.vocab.has_rank, rank)
            out.add(element, self.vocab.has_score, score)
        self._write(out)
        return order

    def _write(self, out: _Out) -> None:
        self._buffer.extend(out)
        self._buffered_calls += 1
        self._known.update(out.created)
        if self._buffered_calls >= self.commit_every:
            self.flush()

    def flush(self) -> int:
        """Commit what is buffered as one transaction; return how many calls are committed.

        A commit that fails (or is interrupted) drops the buffered calls: they are never
        counted in ``committed``, which only ever counts what is in the store."""
        buffer, tf, calls = self._buffer, self._tf, self._buffered_calls
        self._buffer, self._tf, self._buffered_calls = [], [], 0
        if buffer or tf:
            try:
                summary = summary_after(self._summary, buffer)
                with self.store.transaction():
                    self.store.insert(self._writing, buffer)
                    if tf:
                        self.store.write_documents(self._writing, "tf", tf)
                    mark = self.store.write_mark(self._writing)
                    self.store.update_meta(self._writing, **{SUMMARY_KEY: {**summary, "mark": mark}})
                self._summary = summary
            except BaseException as error:
                # The in-memory view may now name individuals that were never stored.
                self._known.clear()
                self._episode = None
                self._plans.clear()
                self._sets.clear()
                if isinstance(error, StoreError):
                    raise LoggingError(f"NEEM {self._public_id}: {error}") from None
                raise
        self.committed += calls
        return self.committed

    @property
    def neem_id(self) -> str:
        """The NEEM's id as everyone else knows it: the one it replaces (kept by the replacement)
        while it is still being written hidden, its own otherwise."""
        return self._replaces or self._writing

    @property
    def writes_to(self) -> str:
        """The NEEM the writes go to now: the hidden staging NEEM while ``replacing``."""
        return self._writing

    @property
    def replacing(self) -> bool:
        """Whether the NEEM is written hidden, to replace ``neem_id`` at ``close()``."""
        return self._replaces is not None

    @property
    def _public_id(self) -> str:
        return repr(self.neem_id)

    def close(self) -> None:
        """End the recording session, commit what is buffered; a replacement NEEM then takes the
        place of the old one."""
        if self._episode is not None:
            out = _Out()
            self._end_episode(out)
            self._buffer.extend(out)  # part of the last call's commit, not a call of its own
        self.flush()
        if self._replaces is not None:
            self.store.swap_in(self._writing, self._replaces, replace=self._may_replace)
            self._writing, self._replaces = self._replaces, None

    def abandon(self) -> None:
        """Give up a replacement before ``close()``: it is dropped and the old NEEM stays as it
        was. For a logger that replaces nothing, the same as ``flush()``."""
        if self._replaces is None:
            self.flush()
            return
        self._buffer, self._tf, self._buffered_calls = [], [], 0
        self.store.drop_neem(self._writing)
        self._writing, self._replaces = self._replaces, None

    def __enter__(self) -> NeemLogger:
        return self

    def __exit__(self, kind: object, *exc: object) -> None:
        if kind is not None and self._replaces is not None:
            self.abandon()
        else:
            self.close()
