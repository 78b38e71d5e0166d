"""KnowRob 2.x document model: triple records, typed values, and the ``p*``/``o*`` closure.

Both backends store exactly the documents built here, so a NEEM written by either one dumps to
the same KnowRob ``triples`` layout (knowrob-2x-facts §3-§5).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from datetime import datetime, timezone
from operator import itemgetter
from typing import Any, Literal

from bson.decimal128 import Decimal128
from bson.int64 import Int64
from bson.objectid import ObjectId

from oracle.namespaces import RDF_IRI, RDFS_IRI

RDF_TYPE = RDF_IRI + "type"
SUBCLASS_OF = RDFS_IRI + "subClassOf"
SUBPROPERTY_OF = RDFS_IRI + "subPropertyOf"
#: Properties whose object is closed over the class/property taxonomy (``o*``) instead of ``p*``.
TAXONOMIC: frozenset[str] = frozenset({RDF_TYPE, SUBCLASS_OF, SUBPROPERTY_OF})
#: The two properties whose assertion changes the taxonomy and so the closures of other documents.
HIERARCHY: frozenset[str] = frozenset({SUBCLASS_OF, SUBPROPERTY_OF})
#: Predicate of KnowRob's per-graph version marker documents (no ``p*``, ``o*`` or scope).
VERSION_PREDICATE = "tripledbVersionString"

INFINITY = math.inf
NumberFormat = Literal["decimal128", "double"]
NUMBER_FORMATS: tuple[str, ...] = ("decimal128", "double")

#: A value as Python code sees it: IRIs and string literals are both ``str``, as in KnowRob.
Value = str | float | int | bool | datetime


#: The graph of the facts a NEEM's logger writes (KnowRob's default ``user`` graph).
USER_GRAPH = "user"


class Triple(tuple):  # type: ignore[type-arg]
    """One assertion to store; ``since``/``until`` are unix seconds of its time scope.

    An immutable ``(s, p, o, graph, since, until)`` tuple rather than a frozen dataclass: the
    logger builds ~40 per action, and a frozen dataclass costs 1.5 us to construct against
    0.3 us for this (docs/store.md, Benchmarks). Not a NamedTuple, so that ``Triple(s, p, o)``
    is the whole required signature (hypothesis builds it from that).
    """

    __slots__ = ()

    def __new__(
        cls, s: str, p: str, o: Value, graph: str = USER_GRAPH, since: float = 0.0, until: float = INFINITY
    ) -> Triple:
        return tuple.__new__(cls, (s, p, o, graph, since, until))

    s: str = property(itemgetter(0))  # type: ignore[assignment]
    p: str = property(itemgetter(1))  # type: ignore[assignment]
    o: Value = property(itemgetter(2))  # type: ignore[assignment]
    graph: str = property(itemgetter(3))  # type: ignore[assignment]
    since: float = property(itemgetter(4))  # type: ignore[assignment]
    until: float = property(itemgetter(5))  # type: ignore[assignment]

    def __getnewargs__(self) -> tuple[Any, ...]:
        return tuple(self)

    def __repr__(self) -> str:
        s, p, o, graph, since, until = self
        return f"Triple(s={s!r}, p={p!r}, o={o!r}, graph={graph!r}, since={since!r}, until={until!r})"


#: What ``Store.insert`` takes: a ``Triple``, or its six values as a plain tuple in the same
#: order (the logger's hot path: a tuple is cheaper to make than a ``Triple``).
TripleRow = tuple[str, str, Value, str, float, float]


@dataclass(frozen=True)
class Annotation:
    """A label, comment or other annotation value, kept in the ``annotations`` collection."""

    s: str
    p: str
    v: Any


@dataclass(frozen=True)
class Var:
    """A variable of a triple pattern; variables with the same name must bind the same value."""

    name: str

    def __post_init__(self) -> None:
        if not self.name or not self.name.replace("_", "a").isalnum():
            raise ValueError(f"variable names must be alphanumeric, got {self.name!r}")


#: Comparison operators of ``Cmp``, spelled as in Prolog (and KnowRob's value operators).
CMP_OPS: tuple[str, ...] = ("<", "=<", ">", ">=")


@dataclass(frozen=True)
class Cmp:
    """The object of a pattern compared with a number: ``o OP value`` (``=<`` as in Prolog),
    and with a second number too when ``op2`` is given (``o OP value and o OP2 value2``).

    Only numeric objects match (numbers of any BSON type, and Dates as unix seconds), as
    KnowRob's ``triple(S, P, >=(V))``; ``var`` (optional) binds the object's value. The
    database evaluates it: an SQL ``WHERE`` on SQLite, a ``$match`` on MongoDB. Two bounds in
    one pattern are one index range (the begins of a slice of a NEEM): as two patterns, the
    first bound alone would drive the scan, to the end of the NEEM.
    """

    op: str
    value: float
    var: Var | None = None
    op2: str | None = None
    value2: float | None = None

    def __post_init__(self) -> None:
        for op, value in self.conditions():
            if op not in CMP_OPS:
                raise ValueError(f"comparison operator must be one of {', '.join(CMP_OPS)}, got {op!r}")
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise ValueError(f"a comparison needs a number, got {value!r}")
        if (self.op2 is None) != (self.value2 is None):
            raise ValueError("a second comparison needs both its operator and its number")

    def conditions(self) -> list[tuple[str, Any]]:
        """The comparisons the object must pass, (operator, number) each."""
        first: list[tuple[str, Any]] = [(self.op, self.value)]
        return first if self.op2 is None or self.value2 is None else [*first, (self.op2, self.value2)]

    def holds(self, value: Any) -> bool:
        return all(_compare(op, value, number) for op, number in self.conditions())


def _compare(op: str, value: Any, number: Any) -> bool:
    if op == "<":
        return bool(value < number)
    if op == "=<":
        return bool(value <= number)
    if op == ">":
        return bool(value > number)
    return bool(value >= number)


#: A pattern term: a variable, a constant, or None for "anything" (an anonymous variable);
#: the object may also be a ``Cmp``.
Term = Var | Value | None


@dataclass(frozen=True)
class TriplePattern:
    """``triple(S, P, O)`` with KnowRob's query semantics (knowrob-2x-facts §5).

    A constant taxonomic P (rdf:type, subClassOf, subPropertyOf) matches ``p`` exactly and a
    bound O against ``o*``; any other constant P matches ``p*`` and O against ``o``. A variable P
    binds the asserted ``p``; a variable O binds the asserted ``o``.
    """

    s: Term = None
    p: Term = None
    o: Term = None
    #: The named graph of the documents read: one name, a tuple of names (any of them: a
    #: graph and its super-graphs, KnowRob's ``graph`` filter) or None (every graph).
    graph: str | tuple[str, ...] | None = None

    def variables(self) -> tuple[str, ...]:
        o = self.o.var if isinstance(self.o, Cmp) else self.o
        return tuple(t.name for t in (self.s, self.p, o) if isinstance(t, Var))


@dataclass(frozen=True)
class Scope:
    """A time window; a fact is visible when its scope overlaps ``[since, until]``."""

    since: float = 0.0
    until: float = INFINITY


def encode_number(value: float, number_format: NumberFormat) -> Decimal128 | float:
    """KnowRob 2.x writes every float as Decimal128 (so Infinity fits); KnowRob 3 as double."""
    if number_format == "double":
        return float(value)
    if math.isinf(value):
        return Decimal128("Infinity" if value > 0 else "-Infinity")
    if math.isnan(value):
        return Decimal128("NaN")
    return Decimal128(repr(float(value)))


def encode_value(value: Value, number_format: NumberFormat) -> Any:
    """A Python value as the BSON value KnowRob would write for it."""
    if isinstance(value, bool) or isinstance(value, str):
        return value
    if isinstance(value, int):
        return value if -(2**31) <= value < 2**31 else Int64(value)
    if isinstance(value, float):
        return encode_number(value, number_format)
    if isinstance(value, datetime):
        return value if value.tzinfo else value.replace(tzinfo=timezone.utc)
    raise TypeError(f"cannot store a {type(value).__name__} as a triple value: {value!r}")


def decode_value(value: Any) -> Any:
    """A stored BSON value as plain Python: Decimal128 and double become float, Int64 int."""
    if isinstance(value, Decimal128):
        return float(value.to_decimal())
    if isinstance(value, Int64):
        return int(value)
    return value


def query_values(value: Value) -> list[Any]:
    """Every BSON form a value may be stored in, so a query finds Decimal128 and double alike."""
    if isinstance(value, bool) or isinstance(value, str):
        return [value]
    if isinstance(value, (int, float)):
        forms: list[Any] = [float(value), encode_number(float(value), "decimal128")]
        if float(value).is_integer() and abs(value) < 2**63:
            forms.append(int(value))
        return forms
    return [encode_value(value, "decimal128")]


def unix_seconds(value: Any) -> float | None:
    """A stored time (Decimal128, double, int or Date) as unix seconds, None when absent."""
    if value is None:
        return None
    if isinstance(value, datetime):
        moment: datetime = value if value.tzinfo is not None else value.replace(tzinfo=timezone.utc)
        return moment.timestamp()
    return float(decode_value(value))


class Hierarchy:
    """The asserted class and property taxonomy of one NEEM, as KnowRob closes it on insert.

    ``parents`` of a term are the ``o*`` lists of its own subClassOf/subPropertyOf documents;
    ``closure(term)`` is the term followed by those, without repeats, which is what KnowRob
    stores as ``o*`` of a type triple and as ``p*`` of a non-taxonomic triple. ``used`` holds
    every term that occurs in some stored closure, so a new edge only triggers the (costly)
    propagation through stored documents when it can change one. Given as a function, ``used``
    is read the first time a new edge asks for it: finding it scans every row of a NEEM (0.2-0.4 s
    at 50,000 actions), which a write that adds no edge (a ranking written back) never needs.
    """

    def __init__(self, edges: Iterable[tuple[str, tuple[Any, ...]]] = (),
                 used: Iterable[Any] | Callable[[], Iterable[Any]] = ()) -> None:  # fmt: skip
        self._parents: dict[str, list[tuple[Any, ...]]] = {}
        self._cache: dict[str, tuple[Any, ...]] = {}
        self._read_used = used if callable(used) else None
        self._used: set[Any] = set() if callable(used) else set(used)
        for subject, closure in edges:
            self._parents.setdefault(subject, []).append(tuple(closure))

    @property
    def used(self) -> set[Any]:
        """Every term in some stored closure (read now if it was given as a function)."""
        if self._read_used is not None:
            read, self._read_used = self._read_used, None
            self._used.update(read())  # beside the terms marked since
        return self._used

    def closure(self, term: Any, *, mark: bool = True) -> tuple[Any, ...]:
        """The closure a document about ``term`` stores; ``mark`` records it as used."""
        cached = self._cache.get(term)
        if cached is not None:
            return cached
        return self._compute(term, mark)

    def _compute(self, term: Any, mark: bool) -> tuple[Any, ...]:
        seen = {term}
        out = [term]
        for parent_closure in self._parents.get(term, ()):
            for item in parent_closure:
                if item not in seen:
                    seen.add(item)
                    out.append(item)
        result = tuple(out)
        if mark:
            self._used.update(result)
            if isinstance(term, str):
                self._cache[term] = result
        return result

    def add_edge(self, subject: str, parent: Any) -> tuple[tuple[Any, ...], tuple[Any, ...]]:
        """Record ``subject ⊑ parent``; return (o* of the new edge document, ancestors gained)."""
        edge_closure = self.closure(parent)
        before = set(self.closure(subject, mark=False))
        self._parents.setdefault(subject, []).append(edge_closure)
        gained = tuple(item for item in edge_closure if item not in before)
        if gained:
            # Every cached closure that passes through the subject grows as well.
            self._cache = {k: v for k, v in self._cache.items() if subject not in v}
        return edge_closure, gained

    def patch_closures(self, subject: str, gained: tuple[Any, ...]) -> None:
        """After propagation: the parent closures stored for other terms that contain ``subject``."""
        for key, closures in self._parents.items():
            self._parents[key] = [extend_closure(c, gained) if subject in c else c for c in closures]
        self._cache = {k: v for k, v in self._cache.items() if subject not in v}


def extend_closure(closure: Iterable[Any], extra: Iterable[Any]) -> tuple[Any, ...]:
    """``closure`` followed by the items of ``extra`` it lacks (KnowRob's $setUnion, order kept)."""
    out = list(closure)
    seen = set(out)
    for item in extra:
        if item not in seen:
            seen.add(item)
            out.append(item)
    return tuple(out)


@dataclass
class DocumentBuilder:
    """Builds KnowRob triple documents with their closures; knows the NEEM's hierarchy."""

    hierarchy: Hierarchy
    number_format: NumberFormat = "decimal128"
    _scope_cache: dict[tuple[float, float], dict[str, Any]] = field(default_factory=dict)

    def scope(self, since: float, until: float) -> dict[str, Any]:
        key = (since, until)
        cached = self._scope_cache.get(key)
        if cached is None:
            cached = {
                "time": {
                    "since": encode_number(since, self.number_format),
                    "until": encode_number(until, self.number_format),
                }
            }
            if len(self._scope_cache) < 1024:
                self._scope_cache[key] = cached
        return cached

    def closures(self, triple: TripleRow) -> tuple[tuple[Any, ...], tuple[Any, ...]]:
        """(p*, o*) of a triple as kb_project computes them (knowrob-2x-facts §5)."""
        _, p, o, _, since, until = triple
        if since > until:
            raise ValueError(f"scope of {triple} ends before it starts")
        if p in TAXONOMIC:
            return (p,), (self.hierarchy.closure(o) if type(o) is str else (o,))
        return self.hierarchy.closure(p), (o,)

    def document(
        self, triple: TripleRow, closures: tuple[tuple[Any, ...], tuple[Any, ...]] | None = None
    ) -> dict[str, Any]:
        """The document KnowRob's kb_project would insert for ``triple`` (without propagation).

        It has no ``_id``: the database assigns one on insert, as for KnowRob's documents.
        """
        s, p, o, graph, since, until = triple
        pstar, ostar = closures if closures is not None else self.closures(triple)
        value = encode_value(o, self.number_format)
        return {
            "s": s,
            "p": p,
            "o": value,
            "p*": list(pstar),
            "o*": [encode_value(v, self.number_format) for v in ostar] if ostar != (o,) else [value],
            "graph": graph,
            "scope": self.scope(since, until),
        }


def version_document(ontology: str, version: str, graph: str) -> dict[str, Any]:
    """KnowRob's marker saying which version of an ontology a graph holds."""
    return {"_id": ObjectId(), "s": ontology, "p": VERSION_PREDICATE, "o": version, "graph": graph}


def annotation_document(annotation: Annotation) -> dict[str, Any]:
    return {"_id": ObjectId(), "s": annotation.s, "p": annotation.p, "v": annotation.v}


def document_scope(doc: Mapping[str, Any]) -> tuple[float, float]:
    """A document's time scope in unix seconds; universal when the document has none (KnowRob 3)."""
    time = (doc.get("scope") or {}).get("time") or {}
    since = unix_seconds(time.get("since"))
    until = unix_seconds(time.get("until"))
    return (0.0 if since is None else since, INFINITY if until is None else until)
