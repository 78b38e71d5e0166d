"""The ontology a NEEM is read with: the one the user gave, checked against what the NEEM
records (``ontology.provenance``), or the recorded one rebuilt or reloaded and checked."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

from oracle.errors import OntologyError
from oracle.ontology.builder import build_ontology
from oracle.ontology.model import OdbOntology, load_ontology
from oracle.ontology.provenance import OntologySource, Recorded, fingerprint


def open_source(source: OntologySource) -> OdbOntology:
    """Rebuild or reload the ontology ``source`` names; a recorded file that is gone is an error
    naming it."""
    for value in (source.owl, source.odb, source.mapping, source.soma):
        if value is not None and not Path(value).exists():
            raise OntologyError(f"{value} is gone; give the ontology again (--ontology or --odb/--mapping)")
    if source.owl is not None:
        return load_ontology(source.owl)
    return build_ontology(source.odb, source.mapping, source.soma)


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
        onto = open_source(recorded.source)
    except OntologyError as error:
        raise OntologyError(f"NEEM {neem_id!r} was logged with {recorded.source.describe()}: {error}") from None
    if fingerprint(onto) != recorded.fingerprint:
        raise OntologyError(
            f"NEEM {neem_id!r} was logged with {recorded.source.describe()}, which has changed since; "
            "give the ontology it was logged with (--ontology or --odb/--mapping)"
        )
    return onto
