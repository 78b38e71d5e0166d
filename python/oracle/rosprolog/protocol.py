"""rosprolog's protocol: the three services KnowRob's clients call, and their answers.

``/rosprolog/query`` opens a query under the client's id (mode ALL_SOLUTIONS or INCREMENTAL),
``/rosprolog/next_solution`` hands out its solutions one at a time (status OK, then NO_SOLUTION;
QUERY_FAILED with the Prolog message; WRONG_ID for an id nobody opened), ``/rosprolog/finish``
closes one id or all (``*``). As in rosprolog, opening always succeeds (``ok`` is false only for
an id already open) and an error of the query is told on ``next_solution``.

What differs from rosprolog's node, and why: this project's Prolog answers pages and keeps no
open query between calls (json_query/2, the same allow-list and time limit as ``/api/prolog``).
So a query starts as soon as it is opened (as rosprolog's engine starts on its claim: the first
solution is computed while the client's ``next_solution`` is on its way), an INCREMENTAL one for
one solution (``once`` costs one solution, as there) and then for the rest in one page; an
ALL_SOLUTIONS one in pages of ``PAGE`` solutions. A later page runs the query again from its offset: a query that
writes should be asked in ALL_SOLUTIONS mode or read only its first solution.
"""

from __future__ import annotations

import threading
from collections import deque
from concurrent.futures import ThreadPoolExecutor
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from oracle.errors import NeemOracleError

#: The modes of ``query`` (json_prolog_msgs/PrologQuery).
ALL_SOLUTIONS = 0
INCREMENTAL = 1
#: The statuses of ``next_solution`` (json_prolog_msgs/PrologNextSolution).
NO_SOLUTION = 0
WRONG_ID = 1
QUERY_FAILED = 2
OK = 3
#: The id ``finish`` takes for every open query.
FINISH_ALL = "*"
#: Solutions asked of Prolog at once beyond an incremental query's first.
PAGE = 1000
#: Queries open at once (every client's together); more are refused until some finish.
MAX_OPEN = 256
#: The three services, by the name after the namespace; ``simple_query`` is ``query`` as the
#: older json_prolog named it (CRAM's and openEASE's older clients call /json_prolog/simple_query).
SERVICES = ("query", "next_solution", "finish", "simple_query")
#: What the doors ask json_query/2 for: the client's text is bound to ``_Q``, never pasted in.
READ_QUERY = "rosprolog_json:rosprolog_solution(_Q, S)"
WRITE_QUERY = "rosprolog_json:rosprolog_solution_writing(_Q, S)"


class DoorError(NeemOracleError):
    """A request the protocol cannot take (a missing or mistyped field, an unknown service)."""


class QueryFailed(NeemOracleError):
    """Prolog could not answer the query (its message goes back as QUERY_FAILED)."""


@dataclass(frozen=True)
class Page:
    """Solutions from ``offset`` on, each the JSON text of one ``{Var: Value}`` object."""

    solutions: list[str]
    more: bool


#: ``ask(text, offset, limit) -> Page`` (QueryFailed when Prolog refuses or fails).
Ask = Callable[[str, int, int], Page]


def page_of(reply: dict[str, Any]) -> Page:
    """json_query's answer to READ_QUERY/WRITE_QUERY as a Page."""
    return Page([str(row["S"]) for row in reply.get("solutions", [])], bool(reply.get("more", False)))


def request(text: str, writes: bool) -> tuple[str, dict[str, Any]]:
    """The query and bindings that ask json_query/2 for ``text``'s rosprolog solutions."""
    return (WRITE_QUERY if writes else READ_QUERY), {"_Q": text}


@dataclass
class _Open:
    """One client's open query: what was fetched and what is left to hand out."""

    text: str
    incremental: bool
    lock: threading.Lock = field(default_factory=threading.Lock)
    waiting: deque[str] = field(default_factory=deque)
    fetched: int = 0
    more: bool = True
    error: str | None = None


class Queries:
    """The open queries of every client of one door (ids are shared, as rosprolog's are)."""

    def __init__(self, ask: Ask, max_open: int = MAX_OPEN, page: int = PAGE) -> None:
        self.ask = ask
        self.max_open = max_open
        self.page = page
        self._lock = threading.Lock()
        self._open: dict[str, _Open] = {}
        # first pages computed ahead; Prolog answers one query at a time, so two threads suffice
        self._ahead = ThreadPoolExecutor(2, thread_name_prefix="rosprolog-first")

    def open_ids(self) -> list[str]:
        with self._lock:
            return list(self._open)

    def query(self, id: str, text: str, mode: int) -> tuple[bool, str]:
        """``(ok, message)``: the query is open under ``id``, to be run on its first solution."""
        with self._lock:
            if id in self._open:
                return False, f"Another query is already being processed with id {id}."
            if len(self._open) >= self.max_open:
                return False, f"{len(self._open)} queries are open, this door's limit; finish some first."
            state = self._open[id] = _Open(text, incremental=mode == INCREMENTAL)
        self._ahead.submit(self._first, state)
        return True, ""

    def next_solution(self, id: str) -> tuple[int, str]:
        """``(status, solution)``: the next solution's JSON text, or why there is none."""
        with self._lock:
            state = self._open.get(id)
        if state is None:
            return WRONG_ID, ""
        with state.lock:  # one fetch at a time per query; other queries go on
            if not state.waiting and state.more and state.error is None:
                self._fetch(state)
            if state.waiting:
                return OK, state.waiting.popleft()
            if state.error is not None:
                return QUERY_FAILED, state.error
            return NO_SOLUTION, ""

    def finish(self, id: str) -> None:
        """Forget ``id`` (every open query for ``*``); an unknown id is no error."""
        with self._lock:
            if id == FINISH_ALL:
                self._open.clear()
            else:
                self._open.pop(id, None)

    def _first(self, state: _Open) -> None:
        with state.lock:
            if state.fetched == 0 and not state.waiting and state.more and state.error is None:
                self._fetch(state)

    def _fetch(self, state: _Open) -> None:
        limit = 1 if state.incremental and state.fetched == 0 else self.page
        try:
            page = self.ask(state.text, state.fetched, limit)
        except QueryFailed as error:
            state.error, state.more = str(error), False
            return
        state.waiting.extend(page.solutions)
        state.fetched += len(page.solutions)
        state.more = page.more

    def call(self, service: str, args: dict[str, Any]) -> dict[str, Any]:
        """One service call by name (``query``, ``next_solution``, ``finish``) with the fields of
        its request, answered with the fields of its response (DoorError for a bad request)."""
        if service in ("query", "simple_query"):
            ok, message = self.query(_text(args, "id"), _text(args, "query"), _mode(args))
            return {"ok": ok, "message": message}
        if service == "next_solution":
            status, solution = self.next_solution(_text(args, "id"))
            return {"status": status, "solution": solution}
        if service == "finish":
            self.finish(_text(args, "id"))
            return {}
        raise DoorError(f"no service {service!r} (rosprolog has {', '.join(SERVICES[:3])})")


def _text(args: dict[str, Any], name: str) -> str:
    value = args.get(name)
    if not isinstance(value, str):
        raise DoorError(f"the request's {name!r} must be a string")
    return value


def _mode(args: dict[str, Any]) -> int:
    value = args.get("mode", ALL_SOLUTIONS)
    if not isinstance(value, int) or isinstance(value, bool):
        raise DoorError("the request's 'mode' must be 0 (ALL_SOLUTIONS) or 1 (INCREMENTAL)")
    return value


__all__ = ["ALL_SOLUTIONS", "Ask", "DoorError", "FINISH_ALL", "INCREMENTAL", "NO_SOLUTION", "OK", "Page",
           "QUERY_FAILED", "Queries", "QueryFailed", "SERVICES", "WRONG_ID", "page_of", "request"]
