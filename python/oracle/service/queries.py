"""Prolog queries off the robot's path: ``/api/prolog`` answered by a separate process.

The engine thread serves the robot; a query that runs to its time limit there held every robot
call behind it. Read-only queries instead go to one child process with its own Prolog engine and
its own read-only connection to the store (SQLite in WAL mode lets it read beside the writer;
the service acknowledges a situation only once it is committed, so the child sees everything
acknowledged). It shares neither the engine thread nor the GIL with the robot's routes. A child
that does not answer within its query's time limit plus ``GRACE_S`` is killed and the next
query starts a new one. Queries that may write (``serve --allow-prolog-writes``) still run on
the engine thread: the service stays the NEEM's only writer.

What a query may cost is bounded in the child, so neither the service nor the other robots pay
for it: Prolog's stacks and table space per query (prolog/json_query.pl), the answer's size
(json_query.pl refuses a page of more than 4,000,000 characters before it leaves Prolog, and
the service reads at most ``ANSWER_BYTES`` from the pipe), and the whole child's address space
(``QUERY_MEMORY`` past what it holds once started, ``RLIMIT_AS``), which also bounds what no
Prolog flag does: atoms, strings and Python's copy of the answer. A child that hits it ends;
the query gets one error and the next query starts a new child. Replies cross the pipe as JSON,
never pickled.
"""

from __future__ import annotations

import json
import multiprocessing
import os
import resource
import threading
from typing import TYPE_CHECKING, Any

from oracle.errors import NeemOracleError
from oracle.paths import prolog_dir

if TYPE_CHECKING:
    from multiprocessing.connection import Connection

    from oracle.bridge import Bridge
    from oracle.ontology import OdbOntology

#: The service's Prolog query module (json_query/2), loaded once into a process's Prolog.
QUERY_MODULE = prolog_dir() / "json_query.pl"
#: How much nicer than the service the query process is: it yields the cores to the robot's
#: calls but still runs on a busy machine (SCHED_IDLE, and nice 10 under the tests' nice 10,
#: starved it at a load of 10-13 on 2 cores).
QUERY_NICENESS = 5
#: Seconds a new query process may take to load Prolog and open the store.
STARTUP_S = 120.0
#: Seconds past a query's own time limit before its process is taken for hung and killed.
GRACE_S = 5.0
#: Bytes of address space the query process may add to what it holds once started (its Python,
#: Prolog and the store): atoms, tables, strings and the answer together.
QUERY_MEMORY = 512 * 1024 * 1024
#: The longest reply the service reads from the query process (json_query.pl refuses an answer of
#: more than 4,000,000 characters first; UTF-8 and the reply's frame fit in this).
ANSWER_BYTES = 16 * 1024 * 1024


class PrologQueryError(NeemOracleError):
    """The query a client sent cannot be run (syntax, an error it raised, its time limit)."""


class PrologRefused(PrologQueryError):
    """The query calls a predicate that is not on the read-only allow-list (HTTP 403)."""


class NoSuchNeem(PrologQueryError):
    """The query names a NEEM the store does not hold (HTTP 404)."""


def ask(bridge: Bridge, query: str, bindings: dict[str, Any], offset: int, limit: int, seconds: float,
        writes: bool) -> dict[str, Any]:
    """A page of the query's solutions through ``bridge`` (json_query/2 checks and runs it)."""
    from oracle.bridge import QueryValueError

    try:
        reply = bridge.json_query(QUERY_MODULE, query, bindings, offset, limit, seconds, writes)
    except QueryValueError as error:
        raise PrologQueryError(str(error)) from None
    if "error" in reply:
        raise (PrologRefused if reply.get("refused") else PrologQueryError)(reply["error"])
    return dict(reply)


class QueryProcess:
    """The child process that answers read-only queries; started on the first query."""

    def __init__(self, store_spec: str | None, ontology: OdbOntology) -> None:
        self.store_spec = store_spec
        self.ontology = ontology
        self._lock = threading.Lock()
        self._process: Any = None
        self._conn: Connection | None = None

    def ask(self, neem: str, query: str, bindings: dict[str, Any], offset: int, limit: int,
            seconds: float) -> dict[str, Any]:
        """The query's page of solutions (blocking: call it off the event loop)."""
        with self._lock:
            conn = self._started()
            conn.send_bytes(json.dumps([neem, query, bindings, offset, limit, seconds]).encode())
            if not conn.poll(seconds + GRACE_S):
                self._kill()
                raise PrologQueryError("the query process did not answer in time; it was restarted")
            try:
                kind, payload = json.loads(conn.recv_bytes(ANSWER_BYTES))
            except (EOFError, OSError, ValueError):  # OSError: a reply longer than ANSWER_BYTES
                self._kill()
                raise PrologQueryError("the query process stopped (a query past its memory or answer limit ends it);"
                                       " the next query starts a new one") from None
        if kind == "ok":
            return dict(payload)
        raise {"refused": PrologRefused, "missing": NoSuchNeem, "query": PrologQueryError}.get(kind, NeemOracleError)(payload)

    def _started(self) -> Connection:
        if self._process is not None and self._process.is_alive() and self._conn is not None:
            return self._conn
        self._kill()
        context = multiprocessing.get_context("spawn")  # no copy of the engine thread's Prolog
        parent, child = context.Pipe()
        self._process = context.Process(target=_serve, args=(child, self.store_spec, self.ontology),
                                        name="oracle-queries", daemon=True)
        self._process.start()
        child.close()
        self._conn = parent
        # its start (Python, Prolog, the store) is not charged to the first query's time limit
        try:
            ready = parent.poll(STARTUP_S) and parent.recv_bytes(64) == b"ready"
        except (EOFError, OSError):
            ready = False
        if not ready:
            self._kill()
            raise PrologQueryError("the query process did not start; the next query tries again")
        return parent

    def _kill(self) -> None:
        if self._process is not None:
            self._process.kill()
            self._process.join(5)
        if self._conn is not None:
            self._conn.close()
        self._process = self._conn = None

    def close(self) -> None:
        with self._lock:
            self._kill()


def _yield_cores() -> None:
    """A query at its limit wants a whole core; the robot's calls must not wait for it."""
    try:
        os.nice(QUERY_NICENESS)
    except OSError:
        pass  # a niceness at its maximum already


def _bound_memory() -> None:
    """The child's address space: what it holds now and ``QUERY_MEMORY`` more (Linux; elsewhere
    only Prolog's own limits hold)."""
    try:
        with open("/proc/self/statm", encoding="ascii") as statm:
            held = int(statm.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")
        resource.setrlimit(resource.RLIMIT_AS, (held + QUERY_MEMORY, held + QUERY_MEMORY))
    except (OSError, ValueError):
        pass


def _reply(conn: Connection, kind: str, payload: Any) -> None:
    conn.send_bytes(json.dumps([kind, payload]).encode())


def _serve(conn: Connection, store_spec: str | None, ontology: OdbOntology) -> None:
    """The child's loop: one request in, one ``(kind, payload)`` out, until the pipe closes."""
    from oracle.bridge import Bridge
    from oracle.store import open_store
    from oracle.store.ids import find_neem

    _yield_cores()
    store = open_store(store_spec, read_only=True)
    bridge: Bridge | None = None
    known = store.neems()
    if known:  # load Prolog now rather than in the first query
        bridge = Bridge(store, known[0].id, ontology)
    _bound_memory()
    conn.send_bytes(b"ready")
    while True:
        try:
            neem, query, bindings, offset, limit, seconds = json.loads(conn.recv_bytes())
        except (EOFError, OSError):
            return
        try:
            found = find_neem(store, neem)
            if found is None:
                raise NoSuchNeem(f"no NEEM {neem!r} in the store")
            if bridge is None or bridge.neem_id != found.id:
                bridge = Bridge(store, found.id, ontology)
            _reply(conn, "ok", ask(bridge, query, bindings, offset, limit, seconds, writes=False))
        except PrologRefused as error:
            _reply(conn, "refused", str(error))
        except NoSuchNeem as error:
            _reply(conn, "missing", str(error))
        except NeemOracleError as error:
            _reply(conn, "query", str(error))
        except MemoryError:  # past RLIMIT_AS in Python's own work (the answer's copy)
            _reply(conn, "query", "the query needed more memory than a service query may use")


__all__ = ["GRACE_S", "NoSuchNeem", "PrologQueryError", "PrologRefused", "QueryProcess", "ask"]
