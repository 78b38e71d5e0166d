"""The foreign predicates Prolog calls in module ``store_python`` (prolog/store/python.pl, the
request channel), each answering from the connected bridge's store; registered by
``oracle.bridge.engine``.

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

The others read and write a NEEM's version markers, the facts' scopes, annotations, poses and
dumps. An exception inside a foreign predicate is caught here and handed over as
``error(Message)``: pyswip would turn it into silent failure.
"""

from __future__ import annotations

import functools
import json
import math
from collections.abc import Callable, Iterator, Sequence
from typing import Any

from oracle.bridge.state import CROSSINGS, STATE, connected
from oracle.bridge.values import error_text, plain, quote_atom, term_text
from oracle.errors import PrologError, StoreError
from oracle.store import Annotation, Cmp, Scope, Store, TriplePattern, Triple, Var
from oracle.store.chunks import MatchChunk

#: Rows per chunk handed to Prolog by one solution of py_match/2.
CHUNK = 5000
#: The pending chunks of each py_match/2 call Prolog may still ask again, by its context key.
_GENERATORS: dict[int, Iterator[str]] = {}
_NEXT_KEY = [1]


def _decode_request(
    req: Sequence[Any],
) -> tuple[str, list[TriplePattern], Scope | None, int | None, int, list[tuple[str, bool]], str | None, bool]:
    neem = plain(req[0])
    s0, s1, limit, n_vars = req[1], req[2], req[3], req[4]
    order = [(f"v{index}", plain(direction) == "desc") for index, direction in req[5]]
    group = None if req[6] == -1 else f"v{req[6]}"
    written = plain(req[7]) == "written"
    patterns = []
    for enc in req[8:]:
        terms: list[Any] = []
        graphs: tuple[str, ...] | None = None
        for kind, value in zip(enc[0::2], enc[1::2]):
            kind = plain(kind)
            if kind == "g":  # the graphs a kb_call graph(G) option reads (store_scope)
                graphs = tuple(str(plain(g)) for g in value)
            elif kind == "v":
                terms.append(Var(f"v{value}"))
            elif kind == "cmp":  # cmp(Op, Number, Var), checked by store_pattern
                op, number, index = value
                terms.append(Cmp(plain(op), number, Var(f"v{index}")))
            elif kind == "cmp2":  # cmp(Op, Number, Op2, Number2, Var): a range, one index range
                op, number, op2, number2, index = value
                terms.append(Cmp(plain(op), number, Var(f"v{index}"), plain(op2), number2))
            else:
                terms.append(plain(value))
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
            reply = error_text(error)
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
                req = json.loads(plain(req))
            chunks = _chunks(connected().store, req)
            first = next(chunks, "r(d,[])")
        except Exception as error:  # handed to Prolog: pyswip would make it silent failure
            out.unify(error_text(error))
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
            out.unify(error_text(error))
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

    bridge = connected()
    neem, merge, graph = plain(req[0]), plain(req[1]), plain(req[2])
    triples = [
        Triple(plain(s), plain(p), plain(o), graph, float(since), float(until))
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

    store = connected().store
    neem, op, graph, ontology, version = (plain(x) for x in req)
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

    bridge = connected()
    neem = plain(req[0])
    for pattern in req[1:]:
        s, p, o = (plain(term[0]) if term else None for term in pattern)
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
    bridge = connected()
    neem, s, p, o = (plain(x) for x in req[:4])
    graphs = {str(plain(g)) for g in req[4]} if len(req) > 4 else None
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
    bridge = connected()
    neem, s, p = (plain(x) for x in req)
    rows = (
        f"[{term_text(a.s)},{term_text(a.p)},{term_text(a.v)}]"
        for a in bridge.store.annotations(neem, s or None, p or None)
    )
    return "[" + ",".join(rows) + "]"


@_foreign
def py_annotate(req: Any) -> str:
    """Store ``[S, P, Value]`` rows in the NEEM's annotations collection (load_owl/1)."""
    bridge = connected()
    neem = plain(req[0])
    rows = [Annotation(plain(s), plain(p), plain(v)) for s, p, v in req[1:]]
    bridge.store.insert_annotations(neem, rows)
    return "[]"


@_foreign
def py_tf(req: Any) -> str:
    """tf reads and writes, as rows ``[Stamp, RefFrame, X, Y, Z, QX, QY, QZ, QW]``:
    ``[Neem, Frame, At]`` the latest transform stamped at or before At (-1: any time), ``[]``
    for none; ``[Neem, Frame, Begin, End]`` every transform stamped in [Begin, End], in time
    order; ``[Neem, Frame, Stamp, Ref, X, Y, Z, QX, QY, QZ, QW, write]`` adds one (``[]``)."""
    from oracle.neem.tf import Pose, pose_at, poses_between, tf_document

    bridge = connected()
    neem, frame = plain(req[0]), plain(req[1])
    if len(req) == 12:
        stamp, ref, *numbers = req[2], plain(req[3]), *(float(v) for v in req[4:11])
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

    bridge = connected()
    action, neem, folder = plain(req[0]), plain(req[1]), plain(req[2])
    try:
        if action == "memorize":
            export_neem(bridge.store, neem, folder)
        else:
            remember_dump(bridge.store, neem, folder)
    except StoreError as error:
        return f"error({term_text(str(error))})"
    return "[]"


def py_request(out: Any) -> bool:
    """The values of the question Python is asking (``STATE["request"]``); fails when none is."""
    CROSSINGS["py_request"] += 1
    request = STATE["request"]
    if request is None:
        return False
    out.unify(request)
    return True


def register() -> None:
    """Register every foreign predicate in module ``store_python`` (once per process)."""
    from pyswip import Prolog

    Prolog.register_foreign(py_match, arity=2, module="store_python", nondeterministic=True)
    for binary in (py_insert, py_retract, py_graph, py_scopes, py_annotations, py_annotate, py_tf, py_dump):
        Prolog.register_foreign(binary, arity=2, module="store_python")
    Prolog.register_foreign(py_request, arity=1, module="store_python")
