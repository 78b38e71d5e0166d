"""The service's engine: the store, the ontology, the one Prolog bridge and the live NEEM
sessions, all owned by one dedicated thread.

pyswip is not thread-safe and a SQLite connection belongs to the thread that opened it
(toolchain-facts §2), so every request's work is a job on ``EngineThread``; the event loop
only parses HTTP and waits. Jobs run in arrival order, which is also what makes the
write-behind of a situation safe: its write is queued before any later request.
"""

from __future__ import annotations

import asyncio
import logging
import threading
import time
from collections.abc import Callable
from concurrent.futures import Future, ThreadPoolExecutor
from typing import Any, TypeVar

from oracle.algorithm.params import Hyperparameters
from oracle.algorithm.predictors import DEFAULT
from oracle.algorithm.prior import Prior
from oracle.answers import something_else_sentence, what_next_sentence, why_not_sentence
from oracle.historycache import HistoryCache
from oracle.bridge import Bridge, HistoryView, LatestSituation
from oracle.errors import NeemOracleError, StoreError
from oracle.neem.writer import NeemLogger
from oracle.timeline import Instant
from oracle.ontology import OdbOntology
from oracle.past.kept import KeptPast
from oracle.ranking import latest_instant, make_predictor
from oracle.service.groupcommit import GroupCommit
from oracle.service.guard import Limits
from oracle.service.queries import PrologQueryError, PrologRefused, ask
from oracle.service.session import NeemSession, moment_of
from oracle.store import Store
from oracle.store.ids import alias_of, find_neem

T = TypeVar("T")
LOG = logging.getLogger("oracle.service")
#: A whole request is one transaction: the logger never commits on its own.
NEVER = 10**9
#: Longest a job queued with ``EngineThread.submit_idle`` yields to the jobs queued before its turn.
IDLE_WITHIN_S = 1.0


class EngineThread:
    """The Prolog thread; ``await run(f, ...)`` runs f there and returns its result.

    There is one per process and it lives as long as the process: the Prolog engine the bridge
    attaches to it (``oracle.bridge.engine.attach_engine``) is attached once and never left behind."""

    _shared: ThreadPoolExecutor | None = None
    #: Jobs queued on the shared thread and not started yet (``submit_idle`` yields to them), and
    #: how many of them are idle work themselves (which yields to none of its kind: two would
    #: otherwise pass the turn to each other until their deadline, spinning the thread).
    _waiting = 0
    _idle = 0
    _count = threading.Lock()

    def __init__(self) -> None:
        if EngineThread._shared is None:
            EngineThread._shared = ThreadPoolExecutor(max_workers=1, thread_name_prefix="oracle-engine")
        self._pool: ThreadPoolExecutor = EngineThread._shared
        #: The group commit of the engine's store (oracle.service.groupcommit), set once it is
        #: open: a job that ran while a group was open answers only after that group's commit.
        self.group: GroupCommit | None = None

    def _queue(self, fn: Callable[..., T], *args: Any) -> Future[T]:
        """fn queued on the thread, counted as waiting until it starts."""
        with EngineThread._count:
            EngineThread._waiting += 1
        try:
            return self._pool.submit(_started, fn, *args)
        except BaseException:  # not queued (the thread shut down): not waiting either
            with EngineThread._count:
                EngineThread._waiting -= 1
            raise

    async def run(self, fn: Callable[..., T], *args: Any) -> T:
        done: tuple[T, Future[None] | None] = await asyncio.wrap_future(self._queue(self._job, fn, args))
        result, pending = done
        if pending is not None:
            await asyncio.wrap_future(pending)
        return result

    def _job(self, fn: Callable[..., T], args: tuple[Any, ...]) -> tuple[T, Future[None] | None]:
        result = fn(*args)
        return result, None if self.group is None else self.group.pending()

    def submit(self, fn: Callable[..., Any], *args: Any) -> None:
        """Queue fn without waiting (its errors are logged, never raised into a request)."""
        future = self._queue(fn, *args)
        future.add_done_callback(_log_failure)

    def busy(self) -> bool:
        """Whether a job other than idle work waits for the thread (on the thread: behind the
        one running)."""
        return EngineThread._waiting - EngineThread._idle > 0

    def submit_idle(self, fn: Callable[[], Any], within: float = IDLE_WITHIN_S) -> None:
        """Queue fn (work nobody waits for, e.g. the warm-up after an action) behind every job
        queued when its turn comes, again and again, but for at most ``within`` seconds: a
        robot's situation queued meanwhile runs first (it computes itself what it needs of that
        work). Its errors are logged."""
        deadline = time.monotonic() + within

        def turn() -> None:
            with EngineThread._count:
                EngineThread._idle -= 1
            if self.busy() and time.monotonic() < deadline:
                queue()  # behind the jobs waiting now
                return
            fn()

        def queue() -> None:
            with EngineThread._count:
                EngineThread._idle += 1
            try:
                self.submit(turn)
            except BaseException:
                with EngineThread._count:
                    EngineThread._idle -= 1
                raise

        queue()

    def call(self, fn: Callable[..., T], *args: Any) -> T:
        """Run fn on the engine thread from another, non-async thread (startup, tests)."""
        done: tuple[T, Future[None] | None] = self._queue(self._job, fn, args).result()
        result, pending = done
        if pending is not None:
            pending.result()
        return result

    def close(self) -> None:
        """Wait for the jobs queued so far and commit the open group, a lingering one included
        (the thread itself stays, see the class docstring)."""
        self.call(lambda: None)
        if self.group is not None:
            self.call(self.group.commit)  # answered once flushed too (``_job``)
            self.group.close()


def _started(fn: Callable[..., T], *args: Any) -> T:
    """fn run on the engine thread, no longer counted as waiting."""
    with EngineThread._count:
        EngineThread._waiting -= 1
    return fn(*args)


def _freeze() -> None:
    """A full collection, then every object alive moved out of the collector's view
    (``gc.freeze``), as at boot: a session's fitted model is some hundred thousand long-lived
    objects, and with 20 sessions open each later full collection scanned them all on the
    engine thread (50-130 ms, the tail of every robot's answer). A frozen object that dies is
    still freed by its reference count; only cyclic garbage among them is never collected
    (sessions are dropped only after a failed commit or when the service stops)."""
    import gc

    gc.collect()
    gc.freeze()


def _log_failure(future: Any) -> None:
    error = future.exception()
    if error is not None:
        # the type only: a message may name the user's tasks or objects, and the log holds ids only
        LOG.error("background write failed: %s", type(error).__name__)


class Engine:
    """The live model of the store. Call its methods on the engine thread only."""

    def __init__(self, store: Store, ontology: OdbOntology, settings: Hyperparameters, method: str = DEFAULT,
                 limits: Limits | None = None, prior: Prior | None = None) -> None:
        self.store = store
        self.limits = limits or Limits()
        self.created = 0
        self.ontology = ontology
        self.settings = settings
        #: The predictor every session fits (``serve --method``; default: the pooled predictor).
        self.method = method
        #: The shared prior every session's predictor ranks with (``serve --prior``; None: none).
        self.prior = prior
        self.sessions: dict[str, NeemSession] = {}
        #: What the answers about the past read of each NEEM, kept while the NEEM is unchanged.
        self.past = KeptPast()
        self._bridge: Bridge | None = None

    def warm_up(self) -> None:
        """Pay at boot what the first answer of a process would pay once, whatever its NEEM: the
        Prolog modules (the answers' odb_past among them, loaded through the newest NEEM's
        bridge), the tablet's words (``KeptPast.lexicon``), the modules an answer imports and
        the question forms' patterns and words (``oracle.past.forms``).
        ``serve`` calls it before it listens; nothing of a NEEM is read."""
        import re

        import oracle.past.ask  # noqa: F401  (imported here once, not by the first question)
        from oracle.errors import NeemOracleError
        from oracle.past.evidence import ensure_loaded
        from oracle.past.forms import FORMS, read_question

        lexicon = self.past.lexicon(self.ontology)
        # the questions' patterns compiled into re's cache and the phrase book's words (no NEEM)
        for form in FORMS:
            for _, pattern in form.patterns:
                re.compile(pattern)
        try:
            read_question("why did you suggest it", self.ontology, lexicon)
        except NeemOracleError:
            pass  # "it" names no task: the words were read all the same
        neems = self.store.neems()
        if neems:
            ensure_loaded(self.bridge(neems[-1].id))

    def close(self) -> int:
        """End every open session's recording session (the logger's ``close``: its actions become
        constituents of the episode's top-level action, whose interval gets its end), as the
        service stops; returns how many were ended. A failure is logged by type and the others
        still end; a request after this opens the NEEM anew, in a new recording session."""
        ended = 0
        for neem, session in list(self.sessions.items()):
            try:
                session.logger.close()
                ended += 1
            except NeemOracleError as error:
                LOG.error("NEEM %s: its recording session did not end: %s", neem, type(error).__name__)
        self.sessions.clear()
        return ended

    # -- NEEMs --------------------------------------------------------------------------------
    def neems(self) -> list[dict[str, Any]]:
        return [{"id": info.id, "name": alias_of(info), "user": info.user, "created_at": info.created_at,
                 "temporary": info.temporary} for info in self.store.neems()]

    def newest(self) -> str | None:
        """The newest NEEM (the page's default when the service was given none)."""
        infos = self.store.neems()
        return max(infos, key=lambda info: (info.created_at or "", info.id)).id if infos else None

    def create(self, user: str, neem: str | None) -> dict[str, Any]:
        """A new NEEM (``neem``: its name; an existing NEEM of that name or id is a LoggingError)."""
        if self.created >= self.limits.new_neems:
            raise Overloaded(429, f"this service has created {self.created} NEEMs, its limit; restart it to make more")
        self._room_for_a_session()
        self.created += 1
        logger = NeemLogger.create(self.store, self.ontology, user=user, neem_id=neem, commit_every=NEVER)
        self.sessions[logger.neem_id] = NeemSession(logger.neem_id, logger, self.ontology,
                                                    make_predictor(self.ontology, self.settings, self.method, self.prior), [])
        return {"id": logger.neem_id, "name": alias_of(self.store.neem(logger.neem_id)), "user": user}

    def resolve(self, neem: str) -> str:
        """The id of the NEEM a request names by id or alias (NotFound when none)."""
        if neem in self.sessions:
            return neem
        found = find_neem(self.store, neem)
        if found is None:
            raise NotFound(f"no NEEM {neem!r} in the store")
        return found.id

    def bridge(self, neem: str) -> Bridge:
        """The one bridge, pointed at ``neem`` (Prolog reads one NEEM at a time)."""
        if self._bridge is None or self._bridge.neem_id != neem:
            self._bridge = Bridge(self.store, neem, self.ontology)
        return self._bridge

    def session(self, name: str, view: HistoryView | None = None) -> NeemSession:
        """The NEEM's live session (``name``: its id or alias), opened on first use: one history
        read, one fit. ``view``: the history read already (service.sliced_jobs.open_session)."""
        session = self.sessions.get(name)
        if session is None:
            neem = self.resolve(name)
            if neem in self.sessions:
                return self.sessions[neem]
            self._room_for_a_session()
            if view is None:
                view = HistoryCache.default().view(self.bridge(neem))
            logger = NeemLogger(self.store, self.ontology, neem, commit_every=NEVER)
            session = NeemSession(neem, logger, self.ontology, make_predictor(self.ontology, self.settings, self.method, self.prior),
                                  view.rows)
            self.sessions[neem] = session
            self._show_latest(session, view.latest)
            _freeze()
        return session

    def _room_for_a_session(self) -> None:
        if len(self.sessions) >= self.limits.sessions:
            raise Overloaded(503, f"{len(self.sessions)} NEEMs are open, this service's limit")

    def _show_latest(self, session: NeemSession, latest: LatestSituation | None) -> None:
        """Rank the NEEM's latest imagined situation (not written: it was ranked when logged), so
        the page has something to show before the robot posts (e.g. right after ``make demo``),
        at the time and part of day ``rank`` ranks it."""
        if latest is None:
            return
        try:
            found, ranking, ms = session.situation(latest["available"], latest_instant(latest, session.logger.clocked))
        except NeemOracleError:
            return  # an old situation, before the last action: nothing current to show
        session.describe(found, ranking, ms)

    # -- answers ------------------------------------------------------------------------------
    def why_not(self, neem: str, task: str, at: Any) -> dict[str, Any]:
        session = self.session(neem)
        call = session.calls([task], "task")[0]
        when = None if at is None else Instant.of(moment_of(at, "at")).seconds
        answer = self.bridge(session.neem).why_not(call.task, list(call.args), when)
        return {"sentence": why_not_sentence(answer), "answer": answer}

    def what_next(self, neem: str) -> dict[str, Any]:
        answer = self.bridge(self.session(neem).neem).what_next()
        return {"sentence": what_next_sentence(answer), "answer": answer}

    def something_else(self, neem: str, task: str | None) -> dict[str, Any]:
        session = self.session(neem)
        bridge = self.bridge(session.neem)
        if task:
            call = session.calls([task], "task")[0]
            answer = bridge.something_else(call.task, list(call.args))
        else:
            answer = bridge.something_else()
        return {"sentence": something_else_sentence(answer), "answer": answer}

    # -- Prolog -------------------------------------------------------------------------------
    def prolog(self, neem: str, query: str, bindings: dict[str, Any], offset: int, limit: int,
               seconds: float, writes: bool = False) -> dict[str, Any]:
        """A page of the query's solutions, run here on the engine thread (the service runs
        read-only queries in its query process instead, service/queries.py); it runs at most
        ``limits.query_seconds`` and only predicates json_query allows (``writes``: also its
        `write` class)."""
        bridge = self.bridge(self.session(neem).neem)  # a NotFound error for a missing NEEM
        return ask(bridge, query, bindings, offset, limit, min(seconds, self.limits.query_seconds), writes)


class NotFound(StoreError):
    """The NEEM a request names is not in the store."""


class Overloaded(NeemOracleError):
    """A limit of the process is reached (``status``: 429 or 503)."""

    def __init__(self, status: int, message: str) -> None:
        super().__init__(message)
        self.status = status


__all__ = ["Engine", "EngineThread", "NotFound", "Overloaded", "PrologQueryError", "PrologRefused"]
