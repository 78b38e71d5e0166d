"""Build the odb ontology: odb objects and tasks as OWL classes under SOMA/DUL (thesis ch. 3).

A build of the same files comes from the user's cache (oracle.ontology.cache); only a build
that is not there makes the graph (oracle.ontology.generate, with rdflib).
"""

from __future__ import annotations

from pathlib import Path

from oracle.errors import OntologyError
from oracle.ontology.model import OdbOntology
from oracle.ontology.provenance import OntologySource
from oracle.ontology.cache import build_key, cached_build
from oracle.files import default_cache_dir
from oracle.ontology.inputs import DEFAULT_MAPPING, DEFAULT_ODB, BuildReport
from oracle.ontology.upper import CORE_TBOX, OFFICIAL_FILES


def build_ontology(
    odb_dir: Path | str | None = None,
    mapping: Path | str | None = None,
    soma_dir: Path | str | None = None,
    cache_dir: Path | None = None,
) -> OdbOntology:
    """Build the odb ontology (defaults: the shipped kitchen odb and mapping, core TBox)."""
    return build_with_report(odb_dir, mapping, soma_dir, cache_dir)[0]


def build_with_report(
    odb_dir: Path | str | None = None,
    mapping: Path | str | None = None,
    soma_dir: Path | str | None = None,
    cache_dir: Path | None = None,
) -> tuple[OdbOntology, BuildReport]:
    """The ontology and what the build did; a build of the same files is loaded from the cache
    (oracle.ontology.cache) instead of being made again."""
    odb_path = Path(odb_dir if odb_dir is not None else DEFAULT_ODB).expanduser()
    mapping_path = Path(mapping if mapping is not None else DEFAULT_MAPPING).expanduser()
    soma_path = None if soma_dir is None else Path(soma_dir).expanduser()
    key = build_key(odb_path, mapping_path, soma_path, CORE_TBOX, OFFICIAL_FILES)
    directory = cache_dir if cache_dir is not None else default_cache_dir()
    onto, report = cached_build(key, directory, lambda: _build(odb_path, mapping_path, soma_dir))
    onto.cache_dir = cache_dir
    onto.source = OntologySource.built(odb_dir, mapping, soma_dir)
    onto.cache_key = key
    return onto, report


def _build(odb_dir: Path, mapping: Path, soma_dir: Path | str | None) -> tuple[OdbOntology, BuildReport]:
    from oracle.ontology.upper import check_upper_files

    check_upper_files(soma_dir)  # a hostile --soma file is refused before rdflib is imported
    from oracle.ontology.generate import check_upper_iris, generate
    from oracle.ontology.mapping import load_mapping
    from oracle.ontology.odb import read_odb
    from oracle.ontology.upper import load_upper

    objects = read_odb(odb_dir)
    maps = load_mapping(mapping)
    upper = load_upper(soma_dir)
    check_upper_iris(maps, upper, "the official SOMA/DUL files" if soma_dir else "the core TBox (pass --soma DIR for the official files)")
    graph, report = generate(objects, maps, upper)
    onto = OdbOntology.from_graph(graph, maps.namespace)
    onto.taxonomy  # noqa: B018 - computed once here, so the cached copy carries it
    return onto, report


def write_ontology(ontology: OdbOntology, out: Path | str) -> Path:
    """Write the ontology as RDF/XML (``.owl``, ``.rdf``, ``.xml``) or Turtle (``.ttl``)."""
    out = Path(out)
    fmt = "turtle" if out.suffix in (".ttl", ".turtle") else "xml"
    try:
        from oracle.files import write_private_bytes

        write_private_bytes(out, ontology.graph.serialize(format=fmt, encoding="utf-8"))
    except OSError as error:
        raise OntologyError(f"{out}: cannot write ({error.strerror})") from None
    return out
