"""A graph as plain JSON data, both ways: its bound prefixes and its triples, each term a string
(an IRI), ``["b", id]`` (a blank node) or ``["l", text, datatype, language]`` (a literal). Read
back, every part is checked before rdflib makes anything of it (``checked_graph``); nothing in the
data names code. Used by the ontology's cache entry (oracle.ontology.plain, oracle.ontology.model).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from rdflib import Graph
    from rdflib.term import Node


class PlainEntryError(ValueError):
    """The data is not what this module (or the cache entry that holds it) wrote."""


def text(value: Any) -> str:
    if not isinstance(value, str):
        raise PlainEntryError(f"expected a string, got {type(value).__name__}")
    return value


def maybe_text(value: Any) -> str | None:
    return None if value is None else text(value)


def texts(value: Any) -> tuple[str, ...]:
    if not isinstance(value, list):
        raise PlainEntryError(f"expected a list, got {type(value).__name__}")
    return tuple(text(v) for v in value)


def rows(value: Any, width: int) -> list[list[Any]]:
    if not isinstance(value, list) or not all(isinstance(row, list) and len(row) == width for row in value):
        raise PlainEntryError(f"expected rows of {width}")
    return value


def graph_to_plain(graph: Graph) -> dict[str, Any]:
    """The graph's bound prefixes and its triples, each term as the module's docstring says."""
    from rdflib import BNode, URIRef

    def term(node: Node) -> Any:
        if isinstance(node, URIRef):
            return str(node)
        if isinstance(node, BNode):
            return ["b", str(node)]
        datatype = getattr(node, "datatype", None)
        return ["l", str(node), None if datatype is None else str(datatype), getattr(node, "language", None)]

    return {"prefixes": [[str(p), str(ns)] for p, ns in graph.namespaces()],
            "triples": [[term(s), term(p), term(o)] for s, p, o in graph]}


def checked_graph(data: Any) -> dict[str, Any]:
    """``data`` when it has the shape ``graph_to_plain`` gives (every prefix and term checked),
    so that a graph made later from it cannot fail; PlainEntryError otherwise."""
    if not isinstance(data, dict):
        raise PlainEntryError("the graph is not a mapping")
    for prefix, namespace in rows(data["prefixes"], 2):
        text(prefix), text(namespace)
    for row in rows(data["triples"], 3):
        for value in row:
            if isinstance(value, str):
                continue
            if isinstance(value, list) and len(value) == 2 and value[0] == "b":
                text(value[1])
            elif isinstance(value, list) and len(value) == 4 and value[0] == "l":
                text(value[1])
                if value[2] is not None and value[3] is not None:
                    raise PlainEntryError("a literal with both a datatype and a language")
                maybe_text(value[2]), maybe_text(value[3])
            else:
                raise PlainEntryError("a term is neither an IRI, a blank node nor a literal")
    return data


def graph_from_plain(data: Any) -> Graph:
    """The rdflib graph ``graph_to_plain`` described (checked by ``_checked_graph``)."""
    from rdflib import BNode, Graph, Literal, URIRef

    def term(value: Any) -> Any:
        if isinstance(value, str):
            return URIRef(value)
        if value[0] == "b":
            return BNode(value[1])
        return Literal(value[1], lang=value[3], datatype=None if value[2] is None else URIRef(value[2]))

    data = checked_graph(data)
    graph = Graph(bind_namespaces="none")
    for prefix, namespace in data["prefixes"]:
        graph.bind(prefix, URIRef(namespace), override=True, replace=True)
    add = graph.add
    for s, p, o in data["triples"]:
        add((term(s), term(p), term(o)))
    return graph
