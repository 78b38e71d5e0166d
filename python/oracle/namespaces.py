"""RDF namespaces used throughout the project, defined once."""

from __future__ import annotations

from rdflib import Namespace
from rdflib.namespace import OWL, RDF, RDFS, XSD

SOMA = Namespace("http://www.ease-crc.org/ont/SOMA.owl#")
DUL = Namespace("http://www.ontologydesignpatterns.org/ont/dul/DUL.owl#")
KNOWROB = Namespace("http://knowrob.org/kb/knowrob.owl#")

#: Namespace of the generated odb ontology unless a mapping names another (thesis appendix A).
DEFAULT_ODB_NAMESPACE = "https://ontology.dlr.de/soma/odb#"

#: Prefixes every mapping may use even when it does not import them.
STANDARD_PREFIXES: dict[str, str] = {
    "soma": str(SOMA),
    "dul": str(DUL),
    "knowrob": str(KNOWROB),
    "owl": str(OWL),
    "rdf": str(RDF),
    "rdfs": str(RDFS),
    "xsd": str(XSD),
}

__all__ = ["SOMA", "DUL", "KNOWROB", "OWL", "RDF", "RDFS", "XSD", "DEFAULT_ODB_NAMESPACE", "STANDARD_PREFIXES"]
