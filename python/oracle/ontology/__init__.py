"""odb + mapping -> OWL ontology under SOMA/DUL, its taxonomy and its distances.

Nothing imported here imports rdflib: a build found in the user's cache loads without it, and
only a build, an OWL file read or written, or a NEEM's TBox needs it (oracle.ontology.generate,
oracle.store.tbox).
"""

from oracle.ontology.builder import build_ontology, build_with_report, write_ontology
from oracle.ontology.inputs import BuildReport
from oracle.ontology.distance import DistanceMatrix, owl_distance
from oracle.ontology.model import ObjectClass, OdbOntology, TaskClass, load_ontology
from oracle.ontology.taxonomy import Taxonomy
from oracle.ontology.vocabulary import Vocabulary

__all__ = [
    "BuildReport", "DistanceMatrix", "ObjectClass", "OdbOntology", "TaskClass", "Taxonomy", "Vocabulary",
    "build_ontology", "build_with_report", "load_ontology", "owl_distance", "write_ontology",
]
