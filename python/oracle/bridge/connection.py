"""``Bridge``: Prolog connected to one NEEM of a store, and the questions the oracle, the
answers, the CLI and the service ask it."""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, cast

from oracle.bridge.engine import attach_engine, ensure_loaded, run
from oracle.bridge.records import HistoryRow, HistoryView, LatestSituation, history_rows
from oracle.bridge.state import LOCK, STATE
from oracle.bridge.values import atom, json_object, json_value, plain_term, python_value, term_value
from oracle.errors import PrologError, StoreError
from oracle.store import Store

if TYPE_CHECKING:
    from oracle.ontology import OdbOntology


class Bridge:
    """Prolog connected to one NEEM of a store. Only one bridge is active per process
    (pyswip's Prolog is process-wide): the one that asked last; Prolog is loaded and pointed at
    the bridge's NEEM on its first question (``_ready``)."""

    def __init__(self, store: Store, neem_id: str, ontology: OdbOntology | None = None) -> None:
        from oracle.store.ids import resolve_neem

        self.store = store
        self.neem_id = resolve_neem(store, neem_id)  # an id or an alias; StoreError when neither
        #: The ontology the Prolog names are set from (set_ontology), None before.
        self.ontology: OdbOntology | None = ontology

    def _ready(self) -> None:
        """Prolog loaded and reading this bridge's NEEM with its ontology's names: done on the
        first question, not when the bridge is made (a rank whose history and fit are kept asks
        none), and again when another bridge was used since."""
        with LOCK:
            attach_engine()
            ensure_loaded()
            STATE["bridge"] = self
            if STATE.get("active") is self:
                return
            STATE["request"] = [atom(self.neem_id)]
            try:
                run("store_python:py_request(R), R = [N], neem_store:store_use_python(N)")
                if self.ontology is not None:
                    STATE["request"] = _ontology_request(self.ontology)
                    run("store_python:py_request(Q), Q = [NS, Rows], odb_names:odb_set_namespace(NS),"
                         " forall(member([T, Ta, R], Rows), odb_names:odb_set_task_roles(T, Ta, R))")
            finally:
                STATE["request"] = None
            STATE["active"] = self

    def set_ontology(self, ontology: OdbOntology) -> None:
        """Tell odb_names the ontology's namespace and which role of each task is which."""
        with LOCK:
            self.ontology = ontology
            if STATE.get("active") is self:
                STATE["active"] = None  # set again before the next question

    def _with_request(self, request: list[Any], query: str) -> list[dict[str, Any]]:
        with LOCK:
            self._ready()
            STATE["request"] = request
            try:
                return run(query)
            finally:
                STATE["request"] = None

    # -- queries ---------------------------------------------------------------------------
    def query(self, text: str, maxresult: int = -1) -> list[dict[str, Any]]:
        """Solutions of a Prolog query the user typed (text is the query, not data)."""
        with LOCK:
            self._ready()
            return [{k: python_value(v) for k, v in row.items()} for row in run(text, maxresult)]

    def run_batch(self, max_answers: int | None = None) -> int:
        """Answer the queries on standard input (a pipe or file) without asking for more; every
        answer, or the first ``max_answers`` of each. Returns 1 when a query raised an error."""
        limit = "inf" if max_answers is None else str(int(max_answers))
        return int(self.query(f"batch_toplevel:batch_queries(user_input, {limit}, S)")[0]["S"])

    def run_goal(self, text: str) -> int:
        """Run a goal once as ``swipl -g`` does: 0 on success, 1 on failure, 2 on an error."""
        rows = self._with_request([text], "store_python:py_request(R), R = [G], batch_toplevel:batch_goal(G, S)")
        return int(rows[0]["S"])

    def ask(self, query: str, request: list[Any]) -> list[dict[str, Any]]:
        """Solutions of ``query``, which reads its values with ``store_python:py_request/1``:
        values a client sent travel as terms and never become query text."""
        with LOCK:
            return [{k: python_value(v) for k, v in row.items()} for row in self._with_request(request, query)]

    def use_module(self, path: Path, loaded: str) -> None:
        """Load the Prolog module file ``path`` into ``user`` unless ``loaded`` (a predicate
        indicator, ``module:name/arity``) is already defined (one question when it is)."""
        if not self.ask(f"current_predicate({loaded})", []):
            self.ask("store_python:py_request(R), R = [F], use_module(user:F)", [atom(str(path))])

    def ask_plain(self, query: str, values: Sequence[Any]) -> list[dict[str, Any]]:
        """``ask`` with plain Python values: a string becomes an atom, None the atom ``none``,
        a number itself (an int stays an int: Prolog's 1 and 1.0 do not unify), a list a list of these."""
        self._ready()  # an engine on this thread before any term is made
        return self.ask(query, [plain_term(value) for value in values])

    def answer(self, request: list[Any]) -> dict[str, Any]:
        """answers:answer_json/1 on a request; values travel as terms."""
        rows = self._with_request(request, "answers:answer_json(J)")
        if not rows:
            raise PrologError(f"Prolog found no answer to {request[0]}")
        return json_object(json_value(rows[0]["J"]), "answers:answer_json/1")

    def why_not(self, task: str, args: Sequence[str], at: float | None = None) -> dict[str, Any]:
        self._ready()  # an engine on this thread before any term is made
        return self.answer([atom("why_not"), atom(task), [atom(a) for a in args],
                            float(at) if at is not None else atom("none")])

    def what_next(self) -> dict[str, Any]:
        self._ready()  # an engine on this thread before any term is made
        return self.answer([atom("what_next")])

    def something_else(self, task: str | None = None, args: Sequence[str] = ()) -> dict[str, Any]:
        self._ready()  # an engine on this thread before any term is made
        return self.answer([atom("something_else"), atom(task or "none"), [atom(a) for a in args]])

    def _json(self, goal: str, first: str = "") -> Any:
        """The JSON text a Prolog goal binds to its last argument, parsed; ``first``: the
        arguments before it (Prolog text, ending in a comma)."""
        rows = self._with_request([], f"{goal}({first}J)")
        if not rows:
            raise PrologError(f"Prolog found no answer to {goal}")
        return json_value(rows[0]["J"])

    def history(self) -> list[HistoryRow]:
        """odb_history:situation_history/1 in one crossing: every executed action in begin order
        as ``{"begin", "end", "call", "part", "available", "mode"}`` (calls in the chain syntax). The
        situations that found the same set available share one list (Prolog writes each set once)."""
        return history_rows(self._json("odb_history:situation_history_json"))

    def history_after(self, after: float) -> list[HistoryRow]:
        """The rows of history() whose action began after ``after``, as history() gives them
        when its row before them began at ``after`` (odb_history:situation_history_after/2):
        a few store queries, from the intervals that began after it."""
        if isinstance(after, bool) or not isinstance(after, (int, float)) or not math.isfinite(after):
            raise PrologError(f"history_after needs a finite number, got {after!r}")
        number = repr(after) if isinstance(after, int) else repr(float(after))
        return history_rows(self._json("odb_history:situation_history_json", f"{number}, "))

    def history_slice(self, after: float | None, until: float | None) -> list[HistoryRow]:
        """The rows of history() whose action began after ``after`` and not after ``until`` (None:
        no bound), as history() gives them when both are begins of its rows
        (odb_history:situation_history_json/3): one slice of a whole read (oracle.slicedread),
        its store queries one index range of begins each."""
        return history_rows(self._json("odb_history:situation_history_json",
                                       f"{_bound(after, 'history_slice')}, {_bound(until, 'history_slice')}, "))

    def history_bounds(self, size: int) -> list[float]:
        """Where to end the slices of the history so that each holds about ``size`` actions
        (odb_history:history_slice_bounds/2): ascending begins of its rows, the last slice's end
        (the history's end) not among them."""
        if isinstance(size, bool) or not isinstance(size, int) or size < 1:
            raise PrologError(f"history_bounds needs a positive number of actions, got {size!r}")
        bounds = self._json("odb_history:history_slice_bounds_json", f"{size}, ")
        return [float(b) if isinstance(b, float) else int(b) for b in bounds]

    def latest_situation(self) -> LatestSituation | None:
        """The latest imagined situation as ``{"begin", "available", "part"}`` (``part``: the
        part of day its interval was logged with, ``none`` if none), or None."""
        value = self._json("odb_history:latest_situation_json")
        if value is None:
            return None
        return cast(LatestSituation, json_object(value, "odb_history:latest_situation_json/1"))

    def history_view(self, after: float | None = None) -> HistoryView:
        """The history (``after``: only its rows after the row that began then, as
        ``history_after``) and the latest imagined situation, in one question
        (odb_history:history_view_json/2)."""
        if after is None:
            reply = self._json("odb_history:history_view_json", "none, ")
        else:
            if isinstance(after, bool) or not isinstance(after, (int, float)) or not math.isfinite(after):
                raise PrologError(f"history_view needs a finite number, got {after!r}")
            reply = self._json("odb_history:history_view_json", f"{after!r}, ")
        return HistoryView(history_rows(reply), reply["latest"])

    def json_query(self, module: Path, query: str, bindings: dict[str, Any], offset: int, limit: int,
                   seconds: float, writes: bool = False) -> dict[str, Any]:
        """json_query:json_query/2 of the service's JSON endpoint (``module``, loaded on first
        use): ``query`` run with ``bindings`` (strings as atoms, numbers, lists of them), its
        solutions from ``offset``, at most ``limit``, within ``seconds`` (``writes``: also the
        predicates it classes as writes). QueryValueError for a binding of another type."""
        self._ready()  # an engine on this thread before any term is made
        if not STATE.get("json_query"):
            self.ask("store_python:py_request(R), R = [F], use_module(user:F)", [atom(str(module))])
            STATE["json_query"] = True
        pairs = [[atom(name), term_value(name, value)] for name, value in bindings.items()]
        rows = self.ask("store_python:py_request(R), json_query:json_query(R, J)",
                        [query, pairs, offset, limit, float(seconds), atom("true" if writes else "false")])
        return json_object(json_value(rows[0]["J"]), "json_query:json_query/2")

    def solutions(self, goal: str, variables: Sequence[str], *, stepwise: bool = False) -> list[tuple[Any, ...]]:
        """All solutions of a kb_call goal (its text) as tuples of the named variables."""
        wrapper = "kb_call_stepwise" if stepwise else "kb_call"
        template = "[" + ",".join(variables) + "]"
        rows = self.query(f"findall({template}, {wrapper}(({goal}), any), Rows__)")
        return [tuple(python_value(v) for v in row) for row in rows[0]["Rows__"]]

    def close(self) -> None:
        with LOCK:
            if STATE["bridge"] is self:
                STATE["bridge"] = None
                if STATE.get("active") is self:
                    STATE["active"] = None
                    run("neem_store:store_use_memory")


def _bound(value: float | None, what: str) -> str:
    """A begin as Prolog text (``none`` for None) that reads back as the same number."""
    if value is None:
        return "none"
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise PrologError(f"{what} needs a finite number, got {value!r}")
    return repr(value)


def _ontology_request(ontology: OdbOntology) -> list[Any]:
    """The namespace and each task's target and reference roles, as odb_names takes them."""
    rows = [[atom(task.iri), atom(task.target_role or "none"), atom(task.ref_role or "none")]
            for task in ontology.tasks.values()]
    return [atom(ontology.namespace), rows]


def connect(store: Store, neem_id: str, ontology: OdbOntology | None = None) -> Bridge:
    """A bridge to ``neem_id``; raises StoreError when the NEEM is missing."""
    try:
        return Bridge(store, neem_id, ontology)
    except StoreError:
        raise
