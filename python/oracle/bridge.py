"""pyswip: the one place Python and Prolog meet.

The Python process owns the store; SWI-Prolog runs the rules in prolog/. The bridge
registers its foreign predicates in module ``store_python`` (prolog/store/python.pl, the
request channel) and nothing else touches them; the main ones:

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
from dataclasses import dataclass
from datetime import datetime
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypedDict, cast

from oracle.errors import PrologError, StoreError
from oracle.paths import prolog_dir
from oracle.store import Annotation, Cmp, Scope, Store, TriplePattern, Triple, Var
from oracle.store.chunks import MatchChunk

if TYPE_CHECKING:
    from oracle.ontology import OdbOntology

#: The Prolog modules under ``paths.prolog_dir()``, in load order (KnowRob's layout: the store's facade
#: neem_store over store/, then lang/, model/; the odb extension in odb/); each is imported into ``user`` so a
#: typed query sees its exports (the facade's re-exports are the same predicates as their home's).
MODULES = ("neem_store", "store/neem", "store/python", "store/pattern", "store/scope", "store/memory", "store/write",
           "store/read", "store/graph", "store/annotations", "store/tf", "json_text", "lang/triple", "lang/scope",
           "lang/query", "lang/holds", "lang/temporal", "lang/db",
           "model/rdfs", "model/event", "model/object", "model/situation", "model/action", "model/interval", "model/tf",
           "model/owl", "model/owl_description", "model/dul_object_types", "model/dul_description", "model/soma_types",
           "model/soma_object", "model/soma_workflow", "model/soma_shape", "model/qudt", "reasoning/plowl",
           "lang/subgraph", "lang/rules", "lang/mongolog", "lang/computable",
           "compat/neem_interface", "compat/urdf", "compat/library/db/mongo/client",
           "odb/names", "odb/calls", "odb/events", "odb/decisions", "odb/history", "answers", "batch_toplevel")
#: Rows per chunk handed to Prolog by one solution of py_match/2.
CHUNK = 5000

_LOCK = threading.RLock()
_STATE: dict[str, Any] = {"bridge": None, "active": None, "loaded": False, "request": None}
_GENERATORS: dict[int, Iterator[str]] = {}
_NEXT_KEY = [1]
#: Crossings between the two languages: ``query``, every question Python asks Prolog; the
#: others, every time Prolog called into Python, per foreign predicate (a py_match counted
#: once, however many chunks it hands over).
CROSSINGS = {"query": 0, "py_match": 0, "py_insert": 0, "py_retract": 0, "py_graph": 0, "py_request": 0,
             "py_scopes": 0, "py_annotations": 0, "py_annotate": 0, "py_tf": 0, "py_dump": 0}


def crossings() -> int:
    """Every crossing so far, both ways (``CROSSINGS``); the py_request a question reads its
    values with is part of the question, not counted again."""
    return sum(count for name, count in CROSSINGS.items() if name != "py_request")


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
            if kind == "g":  # the graphs a kb_call graph(G) option reads (store_scope)
                graphs = tuple(str(_plain(g)) for g in value)
            elif kind == "v":
                terms.append(Var(f"v{value}"))
            elif kind == "cmp":  # cmp(Op, Number, Var), checked by store_pattern
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
            if not isinstance(req, list):  # the request as JSON text (store_python_rows/2)
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
    from pyswip import Prolog

    Prolog.register_foreign(py_match, arity=2, module="store_python", nondeterministic=True)
    for binary in (py_insert, py_retract, py_graph, py_scopes, py_annotations, py_annotate, py_tf, py_dump):
        Prolog.register_foreign(binary, arity=2, module="store_python")
    Prolog.register_foreign(py_request, arity=1, module="store_python")
    folder = prolog_dir()
    paths = [folder / f"{name}.pl" for name in MODULES]
    for path in paths:
        if not path.exists():
            raise PrologError(f"{path}: Prolog module missing")
    if not _load_compiled(folder, paths):
        for path in paths:
            _STATE["request"] = [_atom(str(path))]
            _run("store_python:py_request(R), R = [F], use_module(user:F)")
    _STATE["request"] = None
    _STATE["loaded"] = True


def _load_compiled(folder: Path, paths: list[Path]) -> bool:
    """Load the modules from the user's cache of compiled modules (oracle.modulecache), compiling
    them into it first when the entry for their content is missing; False when the cache cannot
    be used (the caller loads the sources)."""
    from oracle import modulecache

    version = str(_run("current_prolog_flag(version, V)")[0]["V"])
    try:
        compiled = modulecache.compiled_path(folder, version)
        # Loaded means every module's source file is known to Prolog afterwards.
        files = [_atom(str(path.resolve())) for path in paths]
        if compiled.is_file():
            _STATE["request"] = [_atom(str(compiled)), files]
            try:
                if not _run("store_python:py_request(R), R = [F, Fs], catch(load_files(user:F, []), _, fail),"
                            " forall(member(S, Fs), source_file(S))"):
                    raise PrologError(f"{compiled}: does not load")
            except PrologError:
                modulecache.discard(compiled)  # damaged: the sources are loaded, and compiled next time
                raise
            modulecache.loaded(compiled)
            return True
        loader = modulecache.prepare(compiled, paths, quote_atom)
        # qcompile loads the modules, as use_module would, and writes the .qlf beside the loader.
        _STATE["request"] = [_atom(str(loader)), files]
        if not _run("store_python:py_request(R), R = [F, Fs], qcompile(user:F, [include(user)]),"
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

    CROSSINGS["query"] += 1
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
        with _LOCK:
            _attach_engine()
            _ensure_loaded()
            _STATE["bridge"] = self
            if _STATE.get("active") is self:
                return
            _STATE["request"] = [_atom(self.neem_id)]
            try:
                _run("store_python:py_request(R), R = [N], neem_store:store_use_python(N)")
                if self.ontology is not None:
                    _STATE["request"] = _ontology_request(self.ontology)
                    _run("store_python:py_request(Q), Q = [NS, Rows], odb_names:odb_set_namespace(NS),"
                         " forall(member([T, Ta, R], Rows), odb_names:odb_set_task_roles(T, Ta, R))")
            finally:
                _STATE["request"] = None
            _STATE["active"] = self

    def set_ontology(self, ontology: OdbOntology) -> None:
        """Tell odb_names the ontology's namespace and which role of each task is which."""
        with _LOCK:
            self.ontology = ontology
            if _STATE.get("active") is self:
                _STATE["active"] = None  # set again before the next question

    def _with_request(self, request: list[Any], query: str) -> list[dict[str, Any]]:
        with _LOCK:
            self._ready()
            _STATE["request"] = request
            try:
                return _run(query)
            finally:
                _STATE["request"] = None

    # -- queries ---------------------------------------------------------------------------
    def query(self, text: str, maxresult: int = -1) -> list[dict[str, Any]]:
        """Solutions of a Prolog query the user typed (text is the query, not data)."""
        with _LOCK:
            self._ready()
            return [{k: _python_value(v) for k, v in row.items()} for row in _run(text, maxresult)]

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
        with _LOCK:
            return [{k: _python_value(v) for k, v in row.items()} for row in self._with_request(request, query)]

    def use_module(self, path: Path, loaded: str) -> None:
        """Load the Prolog module file ``path`` into ``user`` unless ``loaded`` (a predicate
        indicator, ``module:name/arity``) is already defined (one question when it is)."""
        if not self.ask(f"current_predicate({loaded})", []):
            self.ask("store_python:py_request(R), R = [F], use_module(user:F)", [_atom(str(path))])

    def ask_plain(self, query: str, values: Sequence[Any]) -> list[dict[str, Any]]:
        """``ask`` with plain Python values: a string becomes an atom, None the atom ``none``,
        a number itself (an int stays an int: Prolog's 1 and 1.0 do not unify), a list a list of these."""
        self._ready()  # an engine on this thread before any term is made
        return self.ask(query, [_plain_term(value) for value in values])

    def answer(self, request: list[Any]) -> dict[str, Any]:
        """answers:answer_json/1 on a request; values travel as terms."""
        rows = self._with_request(request, "answers:answer_json(J)")
        if not rows:
            raise PrologError(f"Prolog found no answer to {request[0]}")
        return _json_object(_json_value(rows[0]["J"]), "answers:answer_json/1")

    def why_not(self, task: str, args: Sequence[str], at: float | None = None) -> dict[str, Any]:
        self._ready()  # an engine on this thread before any term is made
        return self.answer([_atom("why_not"), _atom(task), [_atom(a) for a in args],
                            float(at) if at is not None else _atom("none")])

    def what_next(self) -> dict[str, Any]:
        self._ready()  # an engine on this thread before any term is made
        return self.answer([_atom("what_next")])

    def something_else(self, task: str | None = None, args: Sequence[str] = ()) -> dict[str, Any]:
        self._ready()  # an engine on this thread before any term is made
        return self.answer([_atom("something_else"), _atom(task or "none"), [_atom(a) for a in args]])

    def _json(self, goal: str, first: str = "") -> Any:
        """The JSON text a Prolog goal binds to its last argument, parsed; ``first``: the
        arguments before it (Prolog text, ending in a comma)."""
        rows = self._with_request([], f"{goal}({first}J)")
        if not rows:
            raise PrologError(f"Prolog found no answer to {goal}")
        return _json_value(rows[0]["J"])

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

    def latest_situation(self) -> LatestSituation | None:
        """The latest imagined situation as ``{"begin", "available", "part"}`` (``part``: the
        part of day its interval was logged with, ``none`` if none), or None."""
        value = self._json("odb_history:latest_situation_json")
        if value is None:
            return None
        return cast(LatestSituation, _json_object(value, "odb_history:latest_situation_json/1"))

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
        if not _STATE.get("json_query"):
            self.ask("store_python:py_request(R), R = [F], use_module(user:F)", [_atom(str(module))])
            _STATE["json_query"] = True
        pairs = [[_atom(name), _term_value(name, value)] for name, value in bindings.items()]
        rows = self.ask("store_python:py_request(R), json_query:json_query(R, J)",
                        [query, pairs, offset, limit, float(seconds), _atom("true" if writes else "false")])
        return _json_object(_json_value(rows[0]["J"]), "json_query:json_query/2")

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
                if _STATE.get("active") is self:
                    _STATE["active"] = None
                    _run("neem_store:store_use_memory")


def _ontology_request(ontology: OdbOntology) -> list[Any]:
    """The namespace and each task's target and reference roles, as odb_names takes them."""
    rows = [[_atom(task.iri), _atom(task.target_role or "none"), _atom(task.ref_role or "none")]
            for task in ontology.tasks.values()]
    return [_atom(ontology.namespace), rows]


def _json_value(text: str | bytes) -> Any:
    """The JSON text a Prolog goal bound (pyswip hands strings back as str or bytes), parsed."""
    return json.loads(text.decode("utf-8") if isinstance(text, bytes) else text)


def _json_object(value: Any, what: str) -> dict[str, Any]:
    """``value`` when it is a JSON object, else a PrologError naming ``what`` gave it."""
    if not isinstance(value, dict):
        raise PrologError(f"{what} gave {type(value).__name__}, not a JSON object")
    return value


def _atom(text: str) -> Any:
    """A Prolog atom for pyswip (its constructor is untyped; this is the one typed door)."""
    from pyswip import Atom

    make: Callable[[str], Any] = Atom
    return make(text)


def _plain_term(value: Any) -> Any:
    """``Bridge.ask_plain``'s rule for one value."""
    if value is None:
        return _atom("none")
    if isinstance(value, str):
        return _atom(value)
    if isinstance(value, list):
        return [_plain_term(v) for v in value]
    return value


class QueryValueError(PrologError):
    """A value a client bound in a query that Prolog cannot take."""


def _term_value(name: str, value: Any) -> Any:
    if isinstance(value, bool) or value is None:
        raise QueryValueError(f"binding {name}: expected a string (atom) or a number, got {value!r}")
    if isinstance(value, (int, float)):
        return value
    if isinstance(value, str):
        return _atom(value)
    if isinstance(value, list):
        return [_term_value(name, v) for v in value]
    raise QueryValueError(f"binding {name}: expected a string (atom), a number or a list, got {type(value).__name__}")


class HistoryRow(TypedDict):
    """One executed action of the oracle's history (odb_history:situation_history/1), in begin
    order: its interval (unix seconds, or positions on a NEEM's sequence clock), its call in the
    chain syntax (``idle`` for an odb:IdleTask action), the part of the day it was logged with
    (``none`` if not), the calls of the imagined situation it was chosen in (None: none) and who
    performed it (odb_history:action_modes/2: ``user``, ``robot``, ``together`` or ``unknown``)."""

    begin: float
    end: float
    call: str
    part: str
    available: list[str] | None
    mode: str


class LatestSituation(TypedDict):
    """The NEEM's latest imagined situation (odb_history:latest_situation/3): when it began,
    the calls it found available (sorted) and the part of the day it was logged with."""

    begin: float
    available: list[str]
    part: str


@dataclass(frozen=True)
class HistoryView:
    """What the oracle reads of a NEEM: the ``situation_history`` rows (``Bridge.history``) and
    the latest imagined situation (``Bridge.latest_situation``)."""

    rows: list[HistoryRow]
    latest: LatestSituation | None


#: Values per row in odb_history:situation_history_json's flat ``rows``: begin, end, call
#: index, part of day, available set index and mode.
ROW_WIDTH = 6


def history_rows(reply: dict[str, Any]) -> list[HistoryRow]:
    """odb_history:situation_history_json's reply as rows (Bridge.history)."""
    calls: list[str] = reply["calls"]
    sets = [[calls[i] for i in indexes] for indexes in reply["sets"]]
    flat = reply["rows"]
    return [HistoryRow(begin=flat[i], end=flat[i + 1], call=calls[flat[i + 2]], part=flat[i + 3],
                       available=sets[flat[i + 4]] if flat[i + 4] >= 0 else None, mode=flat[i + 5])
            for i in range(0, len(flat), ROW_WIDTH)]


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


__all__ = ["Bridge", "CROSSINGS", "HistoryRow", "HistoryView", "LatestSituation", "QueryValueError", "ROW_WIDTH", "connect", "crossings",
           "quote_atom", "term_text"]
