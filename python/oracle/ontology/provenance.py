"""Which ontology a NEEM was logged with, so it is read with the same one (docs/store.md).

A NEEM's IRIs come from its ontology's namespace: read with another ontology, its history looks
empty and a ranking written back would be wrong. The NEEM's registry entry therefore records
the ontology's sources and a fingerprint of its odb part; readers rebuild it from there by
default and refuse an ontology whose fingerprint differs.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Callable, Mapping
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

    def open(self) -> OdbOntology:
        """Rebuild or reload the ontology; a recorded file that is gone is an error naming it."""
        from oracle.ontology.builder import build_ontology
        from oracle.ontology.model import load_ontology

        for value in (self.owl, self.odb, self.mapping, self.soma):
            if value is not None and not Path(value).exists():
                raise OntologyError(f"{value} is gone; give the ontology again (--ontology or --odb/--mapping)")
        if self.owl is not None:
            return load_ontology(self.owl)
        return build_ontology(self.odb, self.mapping, self.soma)


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


def ontology_for(neem_id: str, meta: Mapping[str, Any], given: OdbOntology | None,
                 fallback: Callable[[], OdbOntology]) -> OdbOntology:
    """The ontology to read NEEM ``neem_id`` with.

    ``given`` is what the user named (None: nothing); ``fallback()`` builds the default for a
    NEEM without a record. A given ontology must match the record; without one the recorded
    ontology is rebuilt and must still match (its files may have changed since).
    """
    recorded = Recorded.from_meta(meta)
    if recorded is None:
        return given if given is not None else fallback()
    if given is not None:
        if fingerprint(given) != recorded.fingerprint:
            raise OntologyError(
                f"NEEM {neem_id!r} was logged with {recorded.source.describe()}, not with the ontology given; "
                "leave the ontology options out to use the NEEM's own"
            )
        return given
    try:
        onto = recorded.source.open()
    except OntologyError as error:
        raise OntologyError(f"NEEM {neem_id!r} was logged with {recorded.source.describe()}: {error}") from None
    if fingerprint(onto) != recorded.fingerprint:
        raise OntologyError(
            f"NEEM {neem_id!r} was logged with {recorded.source.describe()}, which has changed since; "
            "give the ontology it was logged with (--ontology or --odb/--mapping)"
        )
    return onto


def _absolute(path: Path | str | None) -> str | None:
    return None if path is None else str(Path(path).expanduser().resolve())


def check_logged_with(neem_id: str, meta: Mapping[str, Any], onto: OdbOntology) -> None:
    """Logging more into a NEEM needs the ontology it was begun with."""
    recorded = Recorded.from_meta(meta)
    if recorded is not None and fingerprint(onto) != recorded.fingerprint:
        raise OntologyError(f"NEEM {neem_id!r} was logged with {recorded.source.describe()}, not with this ontology")
