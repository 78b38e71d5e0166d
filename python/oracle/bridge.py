"""pyswip: the one place Python and Prolog meet.

The Python process owns the store; SWI-Prolog runs the rules in prolog/. The bridge
registers three foreign predicates in module ``neem_store`` and nothing else touches them:

``py_match(+Request, -Chunk)`` (nondeterministic)
    one conjunction of triple patterns -> ``Store.match`` (one SQL join / one aggregation
    pipeline); each solution of the predicate is a chunk of up to ``CHUNK`` rows.
``py_insert(+Request, -Reply)``
    kb_project's triples -> ``store.project`` (merged with or narrowing the stored scopes).
``py_retract(+Request, -Reply)``
    kb_unproject's patterns -> ``store.project.retract``.
``py_request(-Request)``
    the arguments of the question Python is asking, so values reach Prolog as terms and
    never as query text.

pyswip's traps (toolchain-facts §2) shape the code: outputs are always fresh variables
unified in Prolog, exceptions inside foreign predicates are caught here and handed over as
``error(Message)`` (pyswip would turn them into silent failure), no ``Prolog.query`` runs
inside a foreign predicate, and every use of pyswip holds one process-wide lock.

Why this module is large: every foreign predicate Prolog calls (matching, inserting, the
facts' scopes, annotations, poses) lives here, beside the state and lock they share, so that
pyswip and its traps stay in one module.
"""

from __future__ import annotations

import functools
import json
import math
import threading
from collections.abc import Callable, Iterator, Sequence
from datetime import datetime
from pathlib import Path
from typing import TYPE_CHECKING, Any

from oracle.errors import PrologError, StoreError
from oracle.paths import prolog_dir
from oracle.store import Annotation, Cmp, Scope, Store, TriplePattern, Triple, Var
from oracle.store.chunks import MatchChunk

if TYPE_CHECKING:
    from oracle.ontology import OdbOntology

#: The Prolog modules under ``paths.prolog_dir()``, in load order (KnowRob's layout: lang/, model/; the
#: odb extension in odb/); each is imported into ``user`` so a typed query sees its exports.
MODULES = ("neem_store", "json_text", "lang/triple", "lang/scope", "lang/query", "lang/holds", "lang/temporal", "lang/db",
           "model/rdfs", "model/event", "model/object", "model/situation", "model/action", "model/interval", "model/tf",
           "compat/neem_interface", "compat/urdf", "compat/library/db/mongo/client",
           "odb/names", "odb/calls", "odb/events", "odb/decisions", "odb/history", "answers", "batch_toplevel")
#: Rows per chunk handed to Prolog by one solution of py_match/2.
CHUNK = 5000

_LOCK = threading.RLock()
_STATE: dict[str, Any] = {"bridge": None, "loaded": False, "request": None}
_GENERATORS: dict[int, Iterator[str]] = {}
_NEXT_KEY = [1]
#: How many times Prolog called into Python (crossings), per foreign predicate.
CROSSINGS = {"py_match": 0, "py_insert": 0, "py_retract": 0, "py_graph": 0, "py_request": 0, "py_scopes": 0,
             "py_annotations": 0, "py_annotate": 0, "py_tf": 0, "py_dump": 0}


# -- values ------------------------------------------------------------------------------
def _plain(value: Any) -> Any:
    """A value pyswip handed to Python as the plain value the store expects."""
    from pyswip import Atom

    if isinstance(value, Atom):
        return value.value if isinstance(value.value, str) else value.value.decode("utf-8")
    if isinstance(value, bytes):
        return value.decode("utf-8")
    return value


def quote_atom(text: str) -> str:
    """``text`` as a quoted Prolog atom in pure ASCII (every other character escaped)."""
    if text.isascii() and text.isprintable():
        # The common case (IRIs), per value of every row a query returns: no loop in Python.
        return "'" + text.replace("\\", "\\\\").replace("'", "\\'") + "'"
    out = ["'"]
    for ch in text:
        code = ord(ch)
        if ch == "'" or ch == "\\":
            out.append("\\" + ch)
        elif 32 <= code < 127:
            out.append(ch)
        else:
            out.append(f"\\x{code:x}\\")
    out.append("'")
    return "".join(out)


def term_text(value: Any) -> str:
    """A store value as Prolog term text: IRIs and strings as atoms, numbers as numbers."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "1.5NaN"
        if math.isinf(value):
            return "1.0Inf" if value > 0 else "-1.0Inf"
        text = repr(value)
        if "e" in text and "." not in text.split("e")[0]:
            mantissa, exponent = text.split("e")
            text = f"{mantissa}.0e{exponent}"
        return text
    if isinstance(value, datetime):
        return term_text(value.timestamp())
    if isinstance(value, str):
        return quote_atom(value)
    if value is None:
        return quote_atom("")
    if hasattr(value, "to_decimal"):  # Decimal128 from a store that did not decode it
        return term_text(float(value.to_decimal()))
    return quote_atom(str(value))


def _error_text(error: BaseException) -> str:
    return f"error({quote_atom(str(error) or type(error).__name__)})"


# -- the foreign predicates --------------------------------------------------------------
def _decode_request(
    req: Sequence[Any],
) -> tuple[str, list[TriplePattern], Scope | None, int | None, int, list[tuple[str, bool]], str | None, bool]:
    neem = _plain(req[0])
    s0, s1, limit, n_vars = req[1], req[2], req[3], req[4]
    order = [(f"v{index}", _plain(direction) == "desc") for index, direction in req[5]]
    group = None if req[6] == -1 else f"v{req[6]}"
    written = _plain(req[7]) == "written"
    patterns = []
    for enc in req[8:]:
        terms: list[Any] = []
        graphs: tuple[str, ...] | None = None
        for kind, value in zip(enc[0::2], enc[1::2]):
            kind = _plain(kind)
            if kind == "g":  # the graphs a kb_call graph(G) option reads (neem_store)
                graphs = tuple(str(_plain(g)) for g in value)
            elif kind == "v":
                terms.append(Var(f"v{value}"))
            elif kind == "cmp":  # cmp(Op, Number, Var), checked by neem_store
                op, number, index = value
                terms.append(Cmp(_plain(op), number, Var(f"v{index}")))
            else:
                terms.append(_plain(value))
        s, p, o = terms
        patterns.append(TriplePattern(s, p, o, graphs))
    if s0 == -1 and s1 == -1:
        scope = None
    else:
        # KnowRob asks for facts whose scope CONTAINS [s0, s1] (since =< s0, until >= s1);
        # the store tests overlap (since =< scope.until, until >= scope.since), so the ends
        # are handed over swapped.
        scope = Scope(since=float(s1), until=float(s0))
    return neem, patterns, scope, (None if limit == -1 else int(limit)), int(n_vars), order, group, written


def _chunks(store: Store, req: Sequence[Any]) -> Iterator[str]:
    """The solutions of one request as reply texts of up to ``CHUNK`` rows each, in the
    compact form ``r(d(V1, ..., Vk), Rows)``: each distinct value of the chunk written once in
    ``d``, each row a list of its positions there. A history read returns each task, role and
    plan IRI many times: Prolog then reads small integers instead of long quoted atoms (a
    third of the text at 10,000 actions). A grouped request's reply is
    ``r(d(V1, ..., Vk), g(S1, ..., Sm), Rows)``: each distinct group of values once in ``g``
    (a list of positions in ``d``), and each row's last position, k+j, naming the group Sj
    (10,000 imaginings of a persona share ~760 sets of ~20 plans)."""
    neem, patterns, scope, limit, n_vars, order, group, written = _decode_request(req)
    names = [f"v{i}" for i in range(n_vars)]
    # Only the variables Prolog keeps are converted (the grouped one is the last).
    for chunk in store.match_chunks(neem, patterns, names, scope=scope, limit=limit, order=order, group=group,
                                    written_order=written, size=CHUNK):
        yield _compact(chunk, group is not None)


def _compact(chunk: MatchChunk, grouped: bool) -> str:
    """The reply text of one chunk (see ``_chunks``); positions count from 1, as arg/3 does."""
    values = chunk.values
    texts = ",".join([quote_atom(v) if type(v) is str else term_text(v) for v in values])
    table = f"d({texts})" if texts else "d"
    pos = [str(i) for i in range(1, len(values) + 1)]  # each position's text made once
    if not grouped:
        body = "],[".join([",".join([pos[p] for p in row]) for row in chunk.rows])
        return f"r({table},[[{body}]])" if chunk.rows else f"r({table},[])"
    # A group's values come in no fixed order (Store.match): sorted positions make equal
    # groups one entry.
    sets: dict[tuple[int, ...], str] = {}
    first = len(values) + 1
    rows = []
    for row in chunk.rows:
        members = tuple(sorted(row[-1]))
        at = sets.get(members)
        if at is None:
            at = sets[members] = str(first + len(sets))
        rows.append(",".join([pos[p] for p in row[:-1]] + [at]))
    groups = ",".join(["[" + ",".join([pos[p] for p in members]) + "]" for members in sets])
    body = "],[".join(rows)
    return f"r({table},g({groups}),[[{body}]])" if rows else f"r({table},g,[])"


def _connected() -> Bridge:
    """The bridge whose store Prolog's foreign predicates read (PrologError when none is)."""
    bridge: Bridge | None = _STATE["bridge"]
    if bridge is None:
        raise PrologError("no store is connected to Prolog")
    return bridge


def _foreign(answer: Callable[[Any], str]) -> Callable[[Any, Any], bool]:
    """The foreign predicate ``name(+Request, -Reply)`` of ``answer(Request) -> reply text``:
    counted in CROSSINGS, an error handed to Prolog as its reply (pyswip would make it a silent
    failure)."""

    @functools.wraps(answer)
    def predicate(req: Any, out: Any) -> bool:
        CROSSINGS[answer.__name__] += 1
        try:
            reply = answer(req)
        except Exception as error:
            reply = _error_text(error)
        out.unify(reply)
        return True

    return predicate


def py_match(req: Any, out: Any, handle: Any) -> Any:
    from pyswip.core import PL_FIRST_CALL, PL_PRUNED, PL_REDO, PL_foreign_context, PL_foreign_control, PL_retry

    control = PL_foreign_control(handle)
    if control == PL_PRUNED:
        _GENERATORS.pop(PL_foreign_context(handle), None)
        return True
    if control == PL_FIRST_CALL:
        CROSSINGS["py_match"] += 1
        try:
            if not isinstance(req, list):  # the request as JSON text (neem_store's match/4)
                req = json.loads(_plain(req))
            chunks = _chunks(_connected().store, req)
            first = next(chunks, "r(d,[])")
        except Exception as error:  # handed to Prolog: pyswip would make it silent failure
            out.unify(_error_text(error))
            return True
        key = _NEXT_KEY[0]
        _NEXT_KEY[0] += 1
        _GENERATORS[key] = chunks
        out.unify(first)
        return PL_retry(key)
    if control == PL_REDO:
        key = PL_foreign_context(handle)
        pending = _GENERATORS.get(key)
        try:
            chunk = next(pending, None) if pending is not None else None
        except Exception as error:
            _GENERATORS.pop(key, None)
            out.unify(_error_text(error))
            return True
        if chunk is None:
            _GENERATORS.pop(key, None)
            return False
        out.unify(chunk)
        return PL_retry(key)
    return False


@_foreign
def py_insert(req: Any) -> str:
    """``[Neem, Merge, Graph | [S, P, O, Since, Until]...]``: kb_project's triples into a named
    graph, ``Merge`` being ``union`` or ``intersect`` (store.project)."""
    from oracle.store.project import project

    bridge = _connected()
    neem, merge, graph = _plain(req[0]), _plain(req[1]), _plain(req[2])
    triples = [
        Triple(_plain(s), _plain(p), _plain(o), graph, float(since), float(until))
        for s, p, o, since, until in req[3:]
    ]
    project(bridge.store, neem, triples, merge)
    return "[]"


@_foreign
def py_graph(req: Any) -> str:
    """``[Neem, Op, Graph, Ontology, Version]``: a named graph's version marker (``get`` ->
    ``[[Ontology, Version]...]``, ``set``) or the graph dropped (``drop``), as KnowRob's
    get_ontology_version/set_ontology_version/drop_graph."""
    from oracle.store.model import VERSION_PREDICATE, version_document
    from oracle.store.project import retract

    store = _connected().store
    neem, op, graph, ontology, version = (_plain(x) for x in req)
    rows = []
    if op == "get":
        docs = store.find(neem, p=VERSION_PREDICATE, graph=graph, exact=True)
        rows = [f"[{term_text(d['s'])},{term_text(str(d['o']))}]" for d in docs]
    elif op == "set":
        store.write_documents(neem, "triples", [version_document(ontology, str(version), graph)])
    elif op == "drop":
        retract(store, neem, graph=graph)
    else:
        raise PrologError(f"unknown graph operation {op!r}")
    return "[" + ",".join(rows) + "]"


@_foreign
def py_retract(req: Any) -> str:
    """``[Neem | [[S], [P], [O]]...]``: kb_unproject's patterns, ``[]`` for any value."""
    from oracle.store.project import retract

    bridge = _connected()
    neem = _plain(req[0])
    for pattern in req[1:]:
        s, p, o = (_plain(term[0]) if term else None for term in pattern)
        retract(bridge.store, neem, s, p, o)
    return "[]"


def _scope_number(value: Any) -> float:
    if hasattr(value, "to_decimal"):
        return float(value.to_decimal())
    return float(value)


@_foreign
def py_scopes(req: Any) -> str:
    """The time scopes ``[Since, Until]`` of the documents stating one ground triple (any time,
    KnowRob's p*/o* semantics): what ``G during [S, U]`` with S and U free binds. A fifth
    element lists the graphs read (a kb_call graph(G) option)."""
    bridge = _connected()
    neem, s, p, o = (_plain(x) for x in req[:4])
    graphs = {str(_plain(g)) for g in req[4]} if len(req) > 4 else None
    rows = []
    for doc in bridge.store.find(neem, s, p, o):
        if graphs is not None and doc.get("graph") not in graphs:
            continue
        time = doc.get("scope", {}).get("time", {})
        since = _scope_number(time.get("since", 0.0))
        until = _scope_number(time.get("until", math.inf))
        rows.append(f"[{term_text(since)},{term_text(until)}]")
    return "[" + ",".join(rows) + "]"


@_foreign
def py_annotations(req: Any) -> str:
    """Annotations ``[S, P, Value]`` of a subject and/or property (``''`` for any)."""
    bridge = _connected()
    neem, s, p = (_plain(x) for x in req)
    rows = (
        f"[{term_text(a.s)},{term_text(a.p)},{term_text(a.v)}]"
        for a in bridge.store.annotations(neem, s or None, p or None)
    )
    return "[" + ",".join(rows) + "]"


@_foreign
def py_annotate(req: Any) -> str:
    """Store ``[S, P, Value]`` rows in the NEEM's annotations collection (load_owl/1)."""
    bridge = _connected()
    neem = _plain(req[0])
    rows = [Annotation(_plain(s), _plain(p), _plain(v)) for s, p, v in req[1:]]
    bridge.store.insert_annotations(neem, rows)
    return "[]"


@_foreign
def py_tf(req: Any) -> str:
    """tf reads and writes, as rows ``[Stamp, RefFrame, X, Y, Z, QX, QY, QZ, QW]``:
    ``[Neem, Frame, At]`` the latest transform stamped at or before At (-1: any time), ``[]``
    for none; ``[Neem, Frame, Begin, End]`` every transform stamped in [Begin, End], in time
    order; ``[Neem, Frame, Stamp, Ref, X, Y, Z, QX, QY, QZ, QW, write]`` adds one (``[]``)."""
    from oracle.neem.tf import Pose, pose_at, poses_between, tf_document

    bridge = _connected()
    neem, frame = _plain(req[0]), _plain(req[1])
    if len(req) == 12:
        stamp, ref, *numbers = req[2], _plain(req[3]), *(float(v) for v in req[4:11])
        pose = Pose((numbers[0], numbers[1], numbers[2]), (numbers[3], numbers[4], numbers[5], numbers[6]), ref)
        bridge.store.write_documents(neem, "tf", [tf_document(frame, pose, float(stamp), 0)])
        return "[]"
    if len(req) == 4:
        rows = poses_between(bridge.store, neem, frame, float(req[2]), float(req[3]))
    else:
        at = req[2]
        found = pose_at(bridge.store, neem, frame, None if at == -1 else float(at))
        rows = [] if found is None else [found]
    return "[" + ",".join("[" + ",".join(term_text(v) for v in [stamp, pose.frame, *pose.position, *pose.rotation]) + "]"
                          for stamp, pose in rows) + "]"  # fmt: skip


@_foreign
def py_dump(req: Any) -> str:
    """KnowRob's memorize/1 and remember/1 on the current NEEM: ``[memorize, Neem, Dir]``
    writes its dump to Dir, ``[remember, Neem, Dir]`` adds a dump's documents to it. ``[]``,
    or ``error(Message)``."""
    from oracle.store.dump import export_neem, remember_dump

    bridge = _connected()
    action, neem, folder = _plain(req[0]), _plain(req[1]), _plain(req[2])
    try:
        if action == "memorize":
            export_neem(bridge.store, neem, folder)
        else:
            remember_dump(bridge.store, neem, folder)
    except StoreError as error:
        return f"error({term_text(str(error))})"
    return "[]"


def py_request(out: Any) -> bool:
    CROSSINGS["py_request"] += 1
    request = _STATE["request"]
    if request is None:
        return False
    out.unify(request)
    return True


def _ensure_loaded() -> None:
    """Register the foreign predicates and load the Prolog modules, once per process."""
    if _STATE["loaded"]:
        return
    from pyswip import Atom, Prolog

    Prolog.register_foreign(py_match, arity=2, module="neem_store", nondeterministic=True)
    Prolog.register_foreign(py_insert, arity=2, module="neem_store")
    Prolog.register_foreign(py_retract, arity=2, module="neem_store")
    Prolog.register_foreign(py_graph, arity=2, module="neem_store")
    Prolog.register_foreign(py_request, arity=1, module="neem_store")
    Prolog.register_foreign(py_scopes, arity=2, module="neem_store")
    Prolog.register_foreign(py_annotations, arity=2, module="neem_store")
    Prolog.register_foreign(py_annotate, arity=2, module="neem_store")
    Prolog.register_foreign(py_tf, arity=2, module="neem_store")
    Prolog.register_foreign(py_dump, arity=2, module="neem_store")
    folder = prolog_dir()
    paths = [folder / f"{name}.pl" for name in MODULES]
    for path in paths:
        if not path.exists():
            raise PrologError(f"{path}: Prolog module missing")
    if not _load_compiled(folder, paths):
        for path in paths:
            _STATE["request"] = [Atom(str(path))]
            _run("neem_store:py_request(R), R = [F], use_module(user:F)")
    _STATE["request"] = None
    _STATE["loaded"] = True


def _load_compiled(folder: Path, paths: list[Path]) -> bool:
    """Load the modules from the user's cache of compiled modules (oracle.modulecache), compiling
    them into it first when the entry for their content is missing; False when the cache cannot
    be used (the caller loads the sources)."""
    from pyswip import Atom

    from oracle import modulecache

    version = str(_run("current_prolog_flag(version, V)")[0]["V"])
    try:
        compiled = modulecache.compiled_path(folder, version)
        # Loaded means every module's source file is known to Prolog afterwards.
        files = [Atom(str(path.resolve())) for path in paths]
        if compiled.is_file():
            _STATE["request"] = [Atom(str(compiled)), files]
            try:
                if not _run("neem_store:py_request(R), R = [F, Fs], catch(load_files(user:F, []), _, fail),"
                            " forall(member(S, Fs), source_file(S))"):
                    raise PrologError(f"{compiled}: does not load")
            except PrologError:
                modulecache.discard(compiled)  # damaged: the sources are loaded, and compiled next time
                raise
            modulecache.loaded(compiled)
            return True
        loader = modulecache.prepare(compiled, paths, quote_atom)
        # qcompile loads the modules, as use_module would, and writes the .qlf beside the loader.
        _STATE["request"] = [Atom(str(loader)), files]
        if not _run("neem_store:py_request(R), R = [F, Fs], qcompile(user:F, [include(user)]),"
                    " forall(member(S, Fs), source_file(S))"):
            modulecache.discard(loader)
            raise PrologError(f"{loader}: does not compile")
        modulecache.publish(loader, compiled)
        return True
    except (OSError, PrologError):
        return False  # the cache is an optimisation: a read-only or damaged one loads the sources


def _attach_engine() -> None:
    """Give the calling thread a Prolog engine if it has none. Terms (atoms included) made on a
    thread without one crash the process, and pyswip attaches only inside ``Prolog.query``."""
    from pyswip.core import PL_thread_attach_engine, PL_thread_self

    if PL_thread_self() == -1 and PL_thread_attach_engine(None) == -1:
        raise PrologError("cannot attach a Prolog engine to this thread")


def _run(query: str, maxresult: int = -1) -> list[dict[str, Any]]:
    from pyswip import Prolog
    from pyswip.prolog import PrologError as PySwipError

    try:
        return list(Prolog.query(query, maxresult=maxresult))
    except PySwipError as error:
        raise PrologError(_clean_prolog_error(str(error))) from None


def _clean_prolog_error(text: str) -> str:
    if "neem_store_error" in text:
        start = text.find("neem_store_error(")
        return "store: " + text[start + len("neem_store_error("):].split(")", 1)[0].strip("'\"")
    return text.replace("Caused by: ", "").strip()


class Bridge:
    """Prolog connected to one NEEM of a store. Only one bridge is active per process
    (pyswip's Prolog is process-wide); creating a new one replaces the previous."""

    def __init__(self, store: Store, neem_id: str, ontology: OdbOntology | None = None) -> None:
        from pyswip import Atom

        from oracle.store.ids import resolve_neem

        self.store = store
        self.neem_id = neem_id = resolve_neem(store, neem_id)  # an id or an alias; StoreError when neither
        #: The ontology the Prolog names were set from (set_ontology), None before.
        self.ontology: OdbOntology | None = None
        with _LOCK:
            _attach_engine()
            _ensure_loaded()
            _STATE["bridge"] = self
            self._with_request([Atom(neem_id)], "neem_store:py_request(R), R = [N], neem_store:store_use_python(N)")
            if ontology is not None:
                self.set_ontology(ontology)

    def set_ontology(self, ontology: OdbOntology) -> None:
        """Tell odb_names the ontology's namespace and which role of each task is which."""
        from pyswip import Atom

        self.ontology = ontology

        rows = [
            [Atom(task.iri), Atom(task.target_role or "none"), Atom(task.ref_role or "none")]
            for task in ontology.tasks.values()
        ]
        with _LOCK:
            self._with_request([Atom(ontology.namespace), rows],
                               "neem_store:py_request(Q), Q = [NS, Rows], odb_names:odb_set_namespace(NS),"
                               " forall(member([T, Ta, R], Rows), odb_names:odb_set_task_roles(T, Ta, R))")

    def _with_request(self, request: list[Any], query: str) -> list[dict[str, Any]]:
        with _LOCK:
            _STATE["bridge"] = self
            _STATE["request"] = request
            try:
                return _run(query)
            finally:
                _STATE["request"] = None

    # -- queries ---------------------------------------------------------------------------
    def query(self, text: str, maxresult: int = -1) -> list[dict[str, Any]]:
        """Solutions of a Prolog query the user typed (text is the query, not data)."""
        with _LOCK:
            _STATE["bridge"] = self
            return [{k: _python_value(v) for k, v in row.items()} for row in _run(text, maxresult)]

    def run_batch(self, max_answers: int | None = None) -> int:
        """Answer the queries on standard input (a pipe or file) without asking for more; every
        answer, or the first ``max_answers`` of each. Returns 1 when a query raised an error."""
        limit = "inf" if max_answers is None else str(int(max_answers))
        return int(self.query(f"batch_toplevel:batch_queries(user_input, {limit}, S)")[0]["S"])

    def run_goal(self, text: str) -> int:
        """Run a goal once as ``swipl -g`` does: 0 on success, 1 on failure, 2 on an error."""
        rows = self._with_request([text], "neem_store:py_request(R), R = [G], batch_toplevel:batch_goal(G, S)")
        return int(rows[0]["S"])

    def ask(self, query: str, request: list[Any]) -> list[dict[str, Any]]:
        """Solutions of ``query``, which reads its values with ``neem_store:py_request/1``:
        values a client sent travel as terms and never become query text."""
        with _LOCK:
            return [{k: _python_value(v) for k, v in row.items()} for row in self._with_request(request, query)]

    def answer(self, request: list[Any]) -> dict[str, Any]:
        """answers:answer_json/1 on a request; values travel as terms."""
        rows = self._with_request(request, "answers:answer_json(J)")
        if not rows:
            raise PrologError(f"Prolog found no answer to {request[0]}")
        text = rows[0]["J"]
        return json.loads(text.decode("utf-8") if isinstance(text, bytes) else text)

    def why_not(self, task: str, args: Sequence[str], at: float | None = None) -> dict[str, Any]:
        from pyswip import Atom

        return self.answer([Atom("why_not"), Atom(task), [Atom(a) for a in args],
                            float(at) if at is not None else Atom("none")])

    def what_next(self) -> dict[str, Any]:
        from pyswip import Atom

        return self.answer([Atom("what_next")])

    def something_else(self, task: str | None = None, args: Sequence[str] = ()) -> dict[str, Any]:
        from pyswip import Atom

        return self.answer([Atom("something_else"), Atom(task or "none"), [Atom(a) for a in args]])

    def _json(self, goal: str, first: str = "") -> Any:
        """The JSON text a Prolog goal binds to its last argument, parsed; ``first``: the
        arguments before it (Prolog text, ending in a comma)."""
        rows = self._with_request([], f"{goal}({first}J)")
        if not rows:
            raise PrologError(f"Prolog found no answer to {goal}")
        text = rows[0]["J"]
        return json.loads(text.decode("utf-8") if isinstance(text, bytes) else text)

    def history(self) -> list[dict[str, Any]]:
        """odb_history:situation_history/1 in one crossing: every executed action in begin order
        as ``{"begin", "end", "call", "part", "available"}`` (calls in the chain syntax). The
        situations that found the same set available share one list (Prolog writes each set once)."""
        return history_rows(self._json("odb_history:situation_history_json"))

    def history_after(self, after: float) -> list[dict[str, Any]]:
        """The rows of history() whose action began after ``after``, as history() gives them
        when its row before them began at ``after`` (odb_history:situation_history_after/2):
        a few store queries, from the intervals that began after it."""
        if isinstance(after, bool) or not isinstance(after, (int, float)) or not math.isfinite(after):
            raise PrologError(f"history_after needs a finite number, got {after!r}")
        number = repr(after) if isinstance(after, int) else repr(float(after))
        return history_rows(self._json("odb_history:situation_history_json", f"{number}, "))

    def latest_situation(self) -> dict[str, Any] | None:
        """The latest imagined situation as ``{"begin", "available"}``, or None."""
        return self._json("odb_history:latest_situation_json")

    def solutions(self, goal: str, variables: Sequence[str], *, stepwise: bool = False) -> list[tuple[Any, ...]]:
        """All solutions of a kb_call goal (its text) as tuples of the named variables."""
        wrapper = "kb_call_stepwise" if stepwise else "kb_call"
        template = "[" + ",".join(variables) + "]"
        rows = self.query(f"findall({template}, {wrapper}(({goal}), any), Rows__)")
        return [tuple(_python_value(v) for v in row) for row in rows[0]["Rows__"]]

    def close(self) -> None:
        with _LOCK:
            if _STATE["bridge"] is self:
                _STATE["bridge"] = None
                _run("neem_store:store_use_memory")


def history_rows(reply: dict[str, Any]) -> list[dict[str, Any]]:
    """odb_history:situation_history_json's reply as rows (Bridge.history)."""
    calls: list[str] = reply["calls"]
    sets = [[calls[i] for i in indexes] for indexes in reply["sets"]]
    flat = reply["rows"]
    return [{"begin": flat[i], "end": flat[i + 1], "call": calls[flat[i + 2]], "part": flat[i + 3],
             "available": sets[flat[i + 4]] if flat[i + 4] >= 0 else None}
            for i in range(0, len(flat), 5)]


def _python_value(value: Any) -> Any:
    from pyswip import Atom

    if isinstance(value, Atom):
        return value.value
    if isinstance(value, bytes):
        return value.decode("utf-8")
    if isinstance(value, list):
        return [_python_value(v) for v in value]
    return value


def connect(store: Store, neem_id: str, ontology: OdbOntology | None = None) -> Bridge:
    """A bridge to ``neem_id``; raises StoreError when the NEEM is missing."""
    try:
        return Bridge(store, neem_id, ontology)
    except StoreError:
        raise


__all__ = ["Bridge", "CROSSINGS", "connect", "quote_atom", "term_text"]
