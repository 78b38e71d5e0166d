"""The upper ontology the odb attaches to: the official SOMA/DUL files or the project's core TBox.

The core TBox (``ontology/soma-core.ttl``) holds every SOMA/DUL class and property this project
uses, with the official IRIs and the asserted subclass chains of the official files, so the
project works without them. ``--soma DIR`` loads ``DUL.owl``, ``SOMA.owl`` and ``SOMA-HOME.owl``
from DIR instead.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from oracle.errors import OntologyError
from oracle.handed import Handed, parse_rdf_file
from oracle.paths import data_dir

if TYPE_CHECKING:
    from rdflib import Graph

#: Folder of the shipped data (sample odb, mapping, core TBox, kitchen world).
DATA_DIR = data_dir()
CORE_TBOX = DATA_DIR / "soma-core.ttl"
OFFICIAL_FILES = ("DUL.owl", "SOMA.owl", "SOMA-HOME.owl")


def load_upper(soma_dir: Path | str | None = None) -> Graph:
    """Return the upper TBox: the official files from ``soma_dir`` or the shipped core TBox."""
    from rdflib import Graph

    graph = Graph()
    if soma_dir is None:
        if not CORE_TBOX.exists():
            raise OntologyError(f"{CORE_TBOX}: core TBox missing from the installation")
        graph.parse(CORE_TBOX, format="turtle")
        return graph
    directory = Path(soma_dir)
    if not directory.is_dir():
        raise OntologyError(f"{directory}: SOMA folder not found")
    found = official_files(directory)
    if not any(p.name in ("SOMA.owl", "SOMA-HOME.owl") for p in found):
        raise OntologyError(f"{directory}: neither SOMA.owl nor SOMA-HOME.owl found")
    for path in found:  # a regular file in the folder, its entities bounded (oracle.handed)
        parse_rdf_file(graph, path, "xml", Handed("ontology file", OntologyError, directory))
    return graph


def check_upper_files(soma_dir: Path | str | None) -> None:
    """Refuse the official files of ``soma_dir`` that ``load_upper`` would refuse for their kind,
    size or entities (oracle.handed, oracle.xmlguard), before anything heavier (rdflib, the odb)
    is loaded: a hostile file is one line at once."""
    from oracle.handed import OWL_LIMIT, read_handed
    from oracle.xmlguard import check_entities

    if soma_dir is None or not Path(soma_dir).is_dir():
        return  # load_upper says why
    for path in official_files(soma_dir):
        check_entities(read_handed(path, Handed("ontology file", OntologyError, Path(soma_dir)), OWL_LIMIT), str(path),
                       OntologyError)


def official_files(soma_dir: Path | str) -> list[Path]:
    """The official files of ``soma_dir`` that ``load_upper`` reads, in load order (imports first)."""
    directory = Path(soma_dir)
    return [directory / name for name in OFFICIAL_FILES if (directory / name).exists() or (directory / name).is_symlink()]


def declared_entities(graph: Graph) -> frozenset[str]:
    """IRIs declared as classes or properties in a graph."""
    from rdflib import URIRef
    from rdflib.namespace import OWL, RDF

    kinds = (OWL.Class, OWL.ObjectProperty, OWL.DatatypeProperty, OWL.AnnotationProperty)
    return frozenset(str(s) for kind in kinds for s in graph.subjects(RDF.type, kind) if isinstance(s, URIRef))
