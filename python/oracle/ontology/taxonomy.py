"""The class hierarchy of an ontology as a DAG of named classes (asserted rdfs:subClassOf only).

Anonymous classes (restrictions, intersections) are ignored, as KnowRob's ``o*`` closure ignores
them. Every class without a named parent hangs below ``owl:Thing``, the single root.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Iterable, Mapping
from typing import TYPE_CHECKING

from oracle.errors import OntologyError
from oracle.namespaces import OWL_IRI

if TYPE_CHECKING:
    from rdflib import Graph

THING = OWL_IRI + "Thing"


class Taxonomy:
    """Parents, ancestors and depths of named classes; built once, read many times."""

    def __init__(self, parents: Mapping[str, Iterable[str]]):
        table: dict[str, tuple[str, ...]] = {}
        for child, ps in parents.items():
            named = tuple(sorted({p for p in ps if p != child and p != THING}))
            table[child] = named
        for ps in list(table.values()):
            for p in ps:
                table.setdefault(p, ())
        table.pop(THING, None)
        self._parents = {c: (ps if ps else (THING,)) for c, ps in table.items()}
        self._parents[THING] = ()
        self._depth: dict[str, int] = {}
        self._ancestors: dict[str, dict[str, int]] = {}
        for cls in self._parents:
            self.depth(cls)

    def parent_table(self) -> dict[str, tuple[str, ...]]:
        """Every class with its named parents (``owl:Thing`` for a root): what ``Taxonomy(...)``
        is made from again."""
        return dict(self._parents)

    @classmethod
    def from_graph(cls, graph: Graph) -> Taxonomy:
        from rdflib import URIRef
        from rdflib.namespace import OWL, RDF, RDFS

        parents: dict[str, set[str]] = {}
        for s in graph.subjects(RDF.type, OWL.Class):
            if isinstance(s, URIRef):
                parents.setdefault(str(s), set())
        for s, o in graph.subject_objects(RDFS.subClassOf):
            if isinstance(s, URIRef) and isinstance(o, URIRef):
                parents.setdefault(str(s), set()).add(str(o))
        return cls(parents)

    @property
    def classes(self) -> tuple[str, ...]:
        return tuple(sorted(self._parents))

    def __contains__(self, cls: object) -> bool:
        return cls in self._parents

    def parents(self, cls: str) -> tuple[str, ...]:
        self._require(cls)
        return self._parents[cls]

    def children(self, cls: str) -> tuple[str, ...]:
        self._require(cls)
        return tuple(sorted(c for c, ps in self._parents.items() if cls in ps))

    def depth(self, cls: str) -> int:
        """Number of classes on the longest chain from ``owl:Thing`` (depth 1) down to ``cls``."""
        self._require(cls)
        if cls in self._depth:
            return self._depth[cls]
        # Iterative post-order so deep hierarchies do not hit the recursion limit.
        stack: list[tuple[str, bool]] = [(cls, False)]
        on_stack: set[str] = set()
        while stack:
            node, expanded = stack.pop()
            if node in self._depth:
                continue
            if expanded:
                on_stack.discard(node)
                ps = self._parents[node]
                self._depth[node] = 1 + max((self._depth[p] for p in ps), default=0)
                continue
            if node in on_stack:
                raise OntologyError(f"cyclic rdfs:subClassOf through {node}")
            on_stack.add(node)
            stack.append((node, True))
            for p in self._parents[node]:
                if p not in self._depth:
                    if p in on_stack:
                        raise OntologyError(f"cyclic rdfs:subClassOf through {p} and {node}")
                    stack.append((p, False))
        return self._depth[cls]

    @property
    def max_depth(self) -> int:
        return max(self._depth.values())

    def ancestors(self, cls: str) -> dict[str, int]:
        """Every ancestor including ``cls`` itself, with the fewest subClassOf steps up to it."""
        self._require(cls)
        cached = self._ancestors.get(cls)
        if cached is not None:
            return cached
        found = {cls: 0}
        queue = deque([cls])
        while queue:
            node = queue.popleft()
            for p in self._parents[node]:
                if p not in found:
                    found[p] = found[node] + 1
                    queue.append(p)
        self._ancestors[cls] = found
        return found

    def is_subclass_of(self, cls: str, ancestor: str) -> bool:
        return ancestor in self.ancestors(cls)

    def descendants(self, cls: str) -> tuple[str, ...]:
        self._require(cls)
        return tuple(sorted(c for c in self._parents if cls in self.ancestors(c)))

    def _require(self, cls: str) -> None:
        if cls not in self._parents:
            raise OntologyError(f"unknown class {cls}")
