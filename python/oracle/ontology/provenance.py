"""Which ontology a NEEM was logged with, so it is read with the same one (docs/store.md).

A NEEM's IRIs come from its ontology's namespace: read with another ontology, its history looks
empty and a ranking written back would be wrong. The NEEM's registry entry therefore records
the ontology's sources and a fingerprint of its odb part; readers rebuild it from there by
default and refuse an ontology whose fingerprint differs.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from oracle.errors import OntologyError

if TYPE_CHECKING:  # a type only: model imports this module
    from oracle.ontology.model import OdbOntology

#: Key of the record in a NEEM's registry entry (meta document).
META_KEY = "ontology"


@dataclass(frozen=True)
class OntologySource:
    """Where an ontology came from: an OWL file, or odb + mapping (None: the shipped sample)."""

    odb: str | None = None
    mapping: str | None = None
    soma: str | None = None
    owl: str | None = None

    @staticmethod
    def built(odb: Path | str | None, mapping: Path | str | None, soma: Path | str | None) -> OntologySource:
        return OntologySource(_absolute(odb), _absolute(mapping), _absolute(soma))

    @staticmethod
    def loaded(owl: Path | str) -> OntologySource:
        return OntologySource(owl=_absolute(owl))

    def describe(self) -> str:
        """The command-line options that give this ontology."""
        if self.owl is not None:
            return f"--ontology {self.owl}"
        parts = [f"--{name} {value}" for name, value in (("odb", self.odb), ("mapping", self.mapping),
                                                          ("soma", self.soma)) if value is not None]
        return " ".join(parts) if parts else "the sample kitchen ontology"


@dataclass(frozen=True)
class Recorded:
    """A NEEM's record: the source and the fingerprint of what was built from it."""

    source: OntologySource
    fingerprint: str

    def to_meta(self) -> dict[str, Any]:
        return {"odb": self.source.odb, "mapping": self.source.mapping, "soma": self.source.soma,
                "owl": self.source.owl, "fingerprint": self.fingerprint}  # fmt: skip

    @staticmethod
    def from_meta(meta: Mapping[str, Any]) -> Recorded | None:
        """The record in a NEEM's meta, or None (a NEEM loaded from elsewhere, or logged earlier)."""
        entry = meta.get(META_KEY)
        if not isinstance(entry, Mapping) or not isinstance(entry.get("fingerprint"), str):
            return None
        def text(key: str) -> str | None:
            value = entry.get(key)
            return value if isinstance(value, str) else None

        return Recorded(OntologySource(text("odb"), text("mapping"), text("soma"), text("owl")), entry["fingerprint"])


def fingerprint(onto: OdbOntology) -> str:
    """A hash of what a NEEM's triples depend on: namespace, objects and tasks with their classes.

    Whether the ontology came from odb + mapping or from the OWL file built from them, the
    fingerprint is the same; the upper ontology's other classes do not enter it.
    """
    body = {
        "namespace": onto.namespace,
        "objects": {n: [o.iri, sorted(o.parents), sorted(o.tasks)] for n, o in onto.objects.items()},
        "tasks": {n: [t.iri, t.soma_task, t.target_role, t.ref_role, t.disposition, t.parent]
                  for n, t in onto.tasks.items()},
    }  # fmt: skip
    return hashlib.sha256(json.dumps(body, sort_keys=True).encode()).hexdigest()[:16]


def record_of(onto: OdbOntology) -> Recorded | None:
    """What a new NEEM records about ``onto`` (None for an ontology made in memory)."""
    source = getattr(onto, "source", None)
    return None if source is None else Recorded(source, fingerprint(onto))


def _absolute(path: Path | str | None) -> str | None:
    return None if path is None else str(Path(path).expanduser().resolve())


def check_logged_with(neem_id: str, meta: Mapping[str, Any], onto: OdbOntology) -> None:
    """Logging more into a NEEM needs the ontology it was begun with."""
    recorded = Recorded.from_meta(meta)
    if recorded is not None and fingerprint(onto) != recorded.fingerprint:
        raise OntologyError(f"NEEM {neem_id!r} was logged with {recorded.source.describe()}, not with this ontology")
