"""RDF namespaces used throughout the project, defined once.

The IRIs are plain strings (``*_IRI``), what the store and the NEEM terms need; ``SOMA``,
``DUL``, ``KNOWROB``, ``OWL``, ``RDF``, ``RDFS`` and ``XSD`` are the rdflib Namespaces over
them, made on first use: importing rdflib costs a CLI call (``neems``, ``--help``) more than
the work it does, so only the code that builds or reads graphs pays for it.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # what ``__getattr__`` below makes, for the type checker
    from rdflib import Namespace
    from rdflib.namespace import OWL, RDF, RDFS, XSD

    SOMA: Namespace
    DUL: Namespace
    KNOWROB: Namespace

SOMA_IRI = "http://www.ease-crc.org/ont/SOMA.owl#"
DUL_IRI = "http://www.ontologydesignpatterns.org/ont/dul/DUL.owl#"
KNOWROB_IRI = "http://knowrob.org/kb/knowrob.owl#"
OWL_IRI = "http://www.w3.org/2002/07/owl#"
RDF_IRI = "http://www.w3.org/1999/02/22-rdf-syntax-ns#"
RDFS_IRI = "http://www.w3.org/2000/01/rdf-schema#"
XSD_IRI = "http://www.w3.org/2001/XMLSchema#"

#: Namespace of the generated odb ontology unless a mapping names another (thesis appendix A).
DEFAULT_ODB_NAMESPACE = "https://ontology.dlr.de/soma/odb#"

#: Prefixes every mapping may use even when it does not import them.
STANDARD_PREFIXES: dict[str, str] = {
    "soma": SOMA_IRI,
    "dul": DUL_IRI,
    "knowrob": KNOWROB_IRI,
    "owl": OWL_IRI,
    "rdf": RDF_IRI,
    "rdfs": RDFS_IRI,
    "xsd": XSD_IRI,
}

_OURS = {"SOMA": SOMA_IRI, "DUL": DUL_IRI, "KNOWROB": KNOWROB_IRI}
_RDFLIB_OWN = ("OWL", "RDF", "RDFS", "XSD")


def __getattr__(name: str) -> Any:
    """The rdflib Namespace objects, made (and kept as module attributes) on first use."""
    if name in _OURS:
        from rdflib import Namespace

        value: Any = Namespace(_OURS[name])
    elif name in _RDFLIB_OWN:
        import rdflib.namespace

        value = getattr(rdflib.namespace, name)
    else:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    globals()[name] = value
    return value


__all__ = ["SOMA", "DUL", "KNOWROB", "OWL", "RDF", "RDFS", "XSD", "DEFAULT_ODB_NAMESPACE", "STANDARD_PREFIXES",
           "SOMA_IRI", "DUL_IRI", "KNOWROB_IRI", "OWL_IRI", "RDF_IRI", "RDFS_IRI", "XSD_IRI"]
