"""Writing a NEEM (thesis 3.4-3.5): what the robot perceived, could do, did and predicted, as triples.

``NeemLogger`` turns the robot's calls into one NEEM's triples, keeps the buffer it commits and
the clock, and holds its parts: the individuals it mints and the caches of what exists, which
calls were checked and which plans are known (``neem.individuals``), the recording sessions
(``neem.episodes``); the records they pass (``neem.records``) and the checks of a call
(``neem.checks``) live apart. Reading back lives in ``neem.query``, persisting and wiping in
``neem.lifecycle``, bulk import in ``neem.importing``.

One NEEM per user. Every public call validates first and then writes one transaction, so bad
input raises before anything is written and a killed process loses at most the call in flight.
Every action executes its own task individual with its own roles, as neem-interface writes them,
and the roles classify their objects only during the action (``has_role(O, R) during A``). Plans
(what an imagining found available, what a preference ranked) define one shared task description
per call. Objects and agents are shared by every event of the NEEM. See docs/store.md.
"""

from __future__ import annotations

import re
import uuid
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, Any
from datetime import datetime, timezone

from oracle.chains import TaskCall
from oracle.errors import CorruptStoreError, LoggingError, StoreError
from oracle.neem import terms as T
from oracle.neem.checks import PERFORMERS, check_call, check_performer, check_state
from oracle.neem.episodes import Episodes
from oracle.neem.individuals import Individuals, slug, person_iri
from oracle.neem.lifecycle import wipe_temporary_neems
from oracle.neem.query import summarize_neem, summary_after
from oracle.neem.records import LoggedAction, Target, checked_instant, TripleBuffer, fact_extent
from oracle.neem.tf import Pose, frame_name, tf_document
from oracle.ontology.model import OdbOntology
from oracle.ontology.provenance import META_KEY as ONTOLOGY_KEY, check_logged_with, record_of
from oracle.store import RDF_TYPE, Store, TriplePattern, Var
from oracle.store.base import SUMMARY_KEY
from oracle.store.model import TripleRow
from oracle.store.ids import ALIAS_KEY, alias_of, check_alias, find_neem, is_object_id, new_neem_id, unique_alias
from oracle.timeline import IDLE_THRESHOLD_S, Instant, Moment, has_clock, is_idle_gap, sequence_instant

if TYPE_CHECKING:
    from oracle.store.tbox import TBox  # rdflib: only a NEEM's creation loads it (create)

#: NEEM ids are collection prefixes: no underscores (see store.base.check_neem_id).
_NEEM_SLUG = re.compile(r"[^A-Za-z0-9\-]+")


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
        #: The NEEM the writes go to (a hidden staging NEEM until ``close()`` when it replaces one).
        self._target = Target(neem_id)
        self.idle_threshold = idle_threshold
        self.ns: str = onto.namespace
        self.vocab = onto.vocab
        info = store.neem(neem_id)
        check_logged_with(neem_id, info.meta, onto)
        #: False for a NEEM on the sequence clock (oracle.timeline): its times are positions.
        self.clocked = has_clock(info.meta)
        self.user: str = info.user or "user"
        #: The individuals written, and what is known of them (stored or buffered, checked, planned).
        self.individuals = Individuals(store, onto, self._target, user=self.user, clocked=self.clocked)
        #: The plans of an available set logged before, by the identity of its tuple, which is
        #: kept here so that no other object has that id meanwhile: the rows of a chains file
        #: share one tuple per distinct set (oracle.chains), a persona meets a few hundred.
        self._sets: dict[int, tuple[object, list[str]]] = {}
        #: Latest begin and latest end of the executed actions: actions may overlap, as events
        #: do in KnowRob (two sensors firing at once), but none may start before the one before.
        #: Read from the NEEM when something timed is first logged (``_check_time``): writing
        #: a ranking back (``preference``, stamped with its decision's time) needs neither.
        self._last_begin: Instant | None = None
        self._last_end: Instant | None = None
        self._clock_resumed = False
        #: The recording sessions: the open one and what opening and closing one writes.
        self._episodes = Episodes(self.individuals)
        #: What ``neems`` lists, as committed; moved on with every commit (oracle.neem.query).
        known = summarize_neem(store, neem_id, info)
        self._summary = {"actions": known.actions, "begin": known.begin, "end": known.end}

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
            logger._target.replaces, logger._target.may_replace = neem_id, replace
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

    # -- individuals (oracle.neem.individuals) ----------------------------------------------
    def object_iri(self, name: str) -> str:
        return self.individuals.object_iri(name)

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
        executed = {doc["s"] for doc in self.store.find(self._target.writing, p=RDF_TYPE, o=T.ACTION, exact=True)}
        if not executed:
            return None, None
        begins: list[float] = []
        ends: list[float] = []
        for row in self.store.match(
            self._target.writing,
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
        return checked_instant(max(begins)), checked_instant(max(ends))

    # -- public API -------------------------------------------------------------------------
    def perceive(self, obj: str, at: Moment, pose: Pose | None = None) -> str:
        """The robot perceives an odb object; its type triple is scoped from the first perception.
        With a ``pose`` (thesis future work: raw technical data) the object's transform at that
        moment goes into the NEEM's tf collection, frame = the object IRI's local name."""
        when = checked_instant(at)
        self._check_time(when, f"perception of {obj!r}")
        if pose is not None and not isinstance(pose, Pose):
            raise LoggingError(f"perception of {obj!r}: pose must be a Pose, got {type(pose).__name__}")
        out = TripleBuffer()
        iri = self.individuals.obj(obj, out, when.seconds)
        if pose is not None:
            self._tf_seq += 1
            self._tf.append(tf_document(frame_name(iri), pose, when.seconds, self._tf_seq))
        self._write(out)
        return iri

    def available(self, calls: Iterable[TaskCall | str], at: Moment) -> str:
        """The tasks available at a moment: a MentalAction executing Imagining that
        odb:imagines_situation one ActionExecutionPlan per task (thesis 3.4)."""
        when = checked_instant(at)
        resolved = [self.individuals.resolve(call) for call in calls]
        self._check_time(when, "available tasks")
        out = TripleBuffer()
        action, _ = self.individuals.imagining(resolved, when, out)
        self._write(out)
        return action

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
        ``soma:hasExecutionState``, KnowRob's action_succeeded/1 and kin); None is ``succeeded``:
        an action logged is one done, as neem-interface's mem_event_set_succeeded marks it.
        ``session`` names the recording session (one soma:Episode each); None: the UTC day of
        ``begin`` (one session per time-less log)."""
        call = self.individuals.resolve(call)
        check_state(state)
        check_performer(performed_by)
        if session is not None and (not isinstance(session, str) or not session.strip()):
            raise LoggingError(f"session must be a non-empty string, got {session!r}")
        start = checked_instant(begin)
        stop = start if end is None else checked_instant(end)
        if stop.seconds < start.seconds:
            raise LoggingError(f"{call}: ends ({stop.seconds:.3f}) before it starts ({start.seconds:.3f})")
        self._check_time(start, f"action {call}")
        options: list[TaskCall] = []
        entry = self._sets.get(id(available)) if available is not None else None
        known_plans = entry[1] if entry is not None and entry[0] is available else None
        if available is not None and known_plans is None:
            known = self.individuals.resolved.get  # most options were checked before: skip the call
            options = [known(c) or self.individuals.resolve(c) for c in available]
        if action_id is not None:
            iri = f"{self.ns}Action_{slug(action_id)}"
            if self.individuals.exists(iri):  # stored or buffered (``known``): whatever ``commit_every``
                raise LoggingError(f"duplicate action id {action_id!r} in NEEM {self._public_id}")
        else:
            iri = self.individuals.event("Action")
        out = TripleBuffer()
        if action_id is not None:
            out.created.add(iri)
        idle = None
        if self._last_end is not None and is_idle_gap(self._last_end.seconds, start.seconds, self.idle_threshold):
            idle = self.individuals.idle(self._last_end, start, out)
        imagining, plans = self.individuals.imagining(options, start, out, known_plans) if available is not None else (None, [])
        for arg in call.args:  # objects first: an unknown one raises before the task is built
            out.add(iri, T.PARTICIPANT, self.individuals.obj(arg, out, start.seconds))
        task = self.individuals.executed_task(call, start, stop, out)
        out.add(iri, RDF_TYPE, T.ACTION)
        out.add(iri, RDF_TYPE, T.NAMED_INDIVIDUAL)
        out.add(iri, T.EXECUTES, task)
        self.individuals.performers(iri, task, performed_by, start, stop, out)
        out.add(iri, T.HAS_INTERVAL, self.individuals.interval(start, stop, out))
        self.individuals.state(iri, "succeeded" if state is None else state, out)
        if idle is not None:  # the gap before an action is part of its session
            self._episodes.constituent(idle, start, start, session, out, begin=self._last_end)
        self._episodes.constituent(iri, start, stop, session, out)
        self._write(out)
        if known_plans is None and type(available) is tuple:  # immutable: the same set next time
            if len(self._sets) >= 4096:
                self._sets.clear()
            self._sets[id(available)] = (available, plans)
        self._last_begin = start
        if self._last_end is None or stop.seconds > self._last_end.seconds:
            self._last_end = stop
        return LoggedAction(iri, call, start.seconds, stop.seconds, start.part_of_day, task, idle, imagining)

    def preference(self, ranking: Sequence[tuple[TaskCall | str, float]], at: Moment) -> str:
        """A predicted preference (written by the oracle): a MentalAction executing Reasoning
        that odb:imagines_preference a PreferenceOrder (also typed soma:Order) which soma:orders
        one OrderedElement per task, each soma:encapsulates the task's plan and carries
        odb:hasPreferenceRank (1 = most preferred, the order given) and odb:hasPreferenceScore.
        Returns the PreferenceOrder's IRI.

        ``at`` is the time of the decision ranked; it may lie before actions already logged (a
        recorded NEEM ranked afterwards), so it is not checked against the last action's end and
        does not move the logger's clock."""
        when = checked_instant(at)
        resolved = [(self.individuals.resolve(call), float(score)) for call, score in ranking]
        out = TripleBuffer()
        action = self.individuals.mental(T.REASONING, when, out)
        order = self.individuals.event("PreferenceOrder")
        out.add(action, self.vocab.imagines_preference, order)
        out.add(order, RDF_TYPE, T.PREFERENCE_ORDER)
        out.add(order, RDF_TYPE, T.ORDER)
        for rank, (call, score) in enumerate(resolved, start=1):
            element = f"{order}_{rank}"
            out.add(element, RDF_TYPE, T.ORDERED_ELEMENT)
            out.add(order, T.ORDERS, element)
            out.add(element, T.ENCAPSULATES, self.individuals.plan(call, out, when.seconds))
            out.add(element, self.vocab.has_rank, rank)
            out.add(element, self.vocab.has_score, score)
        self._write(out)
        return order

    def _write(self, out: TripleBuffer) -> None:
        self._buffer.extend(out)
        self._buffered_calls += 1
        self.individuals.known.update(out.created)
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
                    self.store.insert(self._target.writing, buffer)
                    if tf:
                        self.store.write_documents(self._target.writing, "tf", tf)
                    mark = self.store.write_mark(self._target.writing)
                    self.store.update_meta(self._target.writing, **{SUMMARY_KEY: {**summary, "mark": mark}})
                self._summary = summary
            except BaseException as error:
                # The in-memory view may now name individuals that were never stored.
                self.individuals.forget()
                self._episodes.current = None
                self.individuals.plans.clear()
                self._sets.clear()
                if isinstance(error, StoreError) and not isinstance(error, CorruptStoreError):
                    raise LoggingError(f"NEEM {self._public_id}: {error}") from None
                raise
        self.committed += calls
        return self.committed

    @property
    def neem_id(self) -> str:
        """The NEEM's id as everyone else knows it: the one it replaces (kept by the replacement)
        while it is still being written hidden, its own otherwise."""
        return self._target.neem_id

    @property
    def writes_to(self) -> str:
        """The NEEM the writes go to now: the hidden staging NEEM while ``replacing``."""
        return self._target.writing

    @property
    def replacing(self) -> bool:
        """Whether the NEEM is written hidden, to replace ``neem_id`` at ``close()``."""
        return self._target.replaces is not None

    @property
    def _public_id(self) -> str:
        return repr(self.neem_id)

    def close(self) -> None:
        """End the recording session, commit what is buffered; a replacement NEEM then takes the
        place of the old one."""
        if self._episodes.current is not None:
            out = TripleBuffer()
            self._episodes.end(out)
            self._buffer.extend(out)  # part of the last call's commit, not a call of its own
        self.flush()
        if self._target.replaces is not None:
            self.store.swap_in(self._target.writing, self._target.replaces, replace=self._target.may_replace)
            self._target.writing, self._target.replaces = self._target.replaces, None

    def abandon(self) -> None:
        """Give up a replacement before ``close()``: it is dropped and the old NEEM stays as it
        was. For a logger that replaces nothing, the same as ``flush()``."""
        if self._target.replaces is None:
            self.flush()
            return
        self._buffer, self._tf, self._buffered_calls = [], [], 0
        self.store.drop_neem(self._target.writing)
        self._target.writing, self._target.replaces = self._target.replaces, None

    def __enter__(self) -> NeemLogger:
        return self

    def __exit__(self, kind: object, *exc: object) -> None:
        if kind is not None and self._target.replaces is not None:
            self.abandon()
        else:
            self.close()


__all__ = ["PERFORMERS", "LoggedAction", "NeemLogger", "check_call", "check_performer", "check_state", "fact_extent",
           "person_iri"]
