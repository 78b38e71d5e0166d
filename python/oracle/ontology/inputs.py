"""What an ontology build reads when given nothing (the shipped sample kitchen odb and its
mapping) and what a build reports."""

from __future__ import annotations

from dataclasses import dataclass

from oracle.ontology.upper import DATA_DIR

DEFAULT_ODB = DATA_DIR / "kitchen-odb"
DEFAULT_MAPPING = DATA_DIR / "mapping.yaml"


@dataclass(frozen=True)
class BuildReport:
    """What a build did, for the CLI summary and for tests."""

    n_objects: int
    n_abstract: int
    n_tasks: int
    unmapped: tuple[str, ...]
    mapped_absent: tuple[str, ...]
    default_tasks: tuple[str, ...]
    n_triples: int
