"""OWL files into a NEEM as KnowRob 2.x's ``load_owl`` puts them there, so KnowRob finds them
loaded: each file in its own graph (the file's base name, ``SOMA-HOME.owl`` -> ``SOMA-HOME``),
every statement of the file in it, and the ``tripledbVersionString`` marker KnowRob compares
before it drops and reloads a graph: the file's modification time as ``file_version/2`` reads
it (SWI-Prolog's ``set_time_file/3``: whole seconds, written as a Prolog float).
"""

from __future__ import annotations

import functools
import os
from collections.abc import Sequence
from pathlib import Path

from rdflib import Graph, URIRef
from rdflib.namespace import OWL, RDF

from oracle.errors import StoreError
from oracle.handed import Handed, open_handed, parse_rdf_file
from oracle.store.tbox import TBox, tbox_from_graph


def graph_of_file(path: Path | str) -> str:
    """KnowRob's graph name for an ontology file: its base name without the extension."""
    return Path(path).stem


def file_version(path: Path | str) -> str:
    """The version KnowRob records for a local file: its modification time in whole seconds (what
    ``set_time_file(F, [modified(T)], [])`` gives), as Prolog writes that float."""
    try:
        seconds = os.stat(path).st_mtime_ns // 1_000_000_000
    except OSError as error:
        raise StoreError(f"{path}: cannot read the ontology file ({error.strerror})") from None
    return repr(float(seconds))


def tbox_from_file(path: Path | str) -> TBox:
    """One OWL file (RDF/XML, Turtle or N-Triples, by its extension) as load_owl loads it."""
    file = Path(path)
    open_handed(file, Handed("ontology file", StoreError, file.parent)).close()  # before resolve(): no link
    stat = _stat(file)
    return _converted(str(file.resolve()), stat[0], stat[1])


def tbox_from_files(paths: Sequence[Path | str]) -> TBox:
    """Several files, each in its own graph with its own marker, loaded as one (parents first)."""
    return TBox.combined([tbox_from_file(path) for path in paths])


def _stat(file: Path) -> tuple[int, int]:
    try:
        st = file.stat()
    except OSError as error:
        raise StoreError(f"{file}: cannot read the ontology file ({error.strerror})") from None
    return st.st_mtime_ns, st.st_size


#: Parsing SOMA-HOME.owl takes seconds; every NEEM of an import or of the service stores the
#: same files, so a file is converted once per process for each (path, mtime, size) it has.
@functools.lru_cache(maxsize=16)
def _converted(path: str, mtime_ns: int, size: int) -> TBox:
    file = Path(path)
    graph = Graph()
    fmt = {".ttl": "turtle", ".nt": "nt"}.get(file.suffix.lower(), "xml")
    # a regular file in its folder, at most OWL_LIMIT bytes, its entities bounded (oracle.handed)
    parse_rdf_file(graph, file, fmt, Handed("ontology file", StoreError, file.parent))
    ontologies = [s for s in graph.subjects(RDF.type, OWL.Ontology) if isinstance(s, URIRef)]
    if not ontologies:
        raise StoreError(f"{file}: declares no owl:Ontology (KnowRob's load_owl refuses such a file)")
    return tbox_from_graph(graph, graph_of_file(file), one_graph=True, version=file_version(file))


__all__ = ["file_version", "graph_of_file", "tbox_from_file", "tbox_from_files"]
