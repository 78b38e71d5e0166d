"""The TBox a NEEM logged with an ontology stores, kept in the user's cache beside the build.

Built with ``--soma DIR``, it is the official files as KnowRob's ``load_owl`` loads each
(``store.owlfile``) plus the odb's own axioms; else the ontology's graph (``store.tbox``).
"""

from __future__ import annotations

import hashlib
import sys
from pathlib import Path
from datetime import datetime
from typing import TYPE_CHECKING, Any

from oracle.files import cached_plain
from oracle.store.model import Annotation, Triple, Value
from oracle.store.tbox import TBox, tbox_from_graph

if TYPE_CHECKING:
    from oracle.ontology.model import OdbOntology

#: Bumped when the layout of a cached TBox changes.
_CACHE_FORMAT = "2"
#: The code a TBox is made with: an edit to any of these makes a new cache entry.
_CODE = ("store/tbox.py", "store/owlfile.py", "store/ontology_tbox.py", "store/model.py", "namespaces.py")


def tbox_for(onto: OdbOntology) -> TBox:
    """What a NEEM logged with ``onto`` stores (``_converted``), from the user's cache when the
    ontology came from a cached build: keyed by that build's key (a hash of every file the build
    reads and of its code) and by the code that converts, so an entry is never stale. An entry
    that is missing, damaged or not the user's own is made again; a cache that cannot be written
    only makes every call convert."""
    key = _cache_key(onto)
    if key is None:
        return _converted(onto)
    from oracle.files import default_cache_dir

    folder = onto.cache_dir if onto.cache_dir is not None else default_cache_dir()
    return cached_plain(folder / f"tbox-{key}.json", key, lambda: _converted(onto), _plain, _from_plain, "tbox-*.json",
                        former="tbox-*.pickle")  # the pickles kept until 2026-12-08 go


def _cache_key(onto: OdbOntology) -> str | None:
    """The key of ``onto``'s TBox, or None for an ontology that came from no cached build (an
    OWL file, or a build whose inputs could not all be read)."""
    if onto.cache_key is None:
        return None
    package = Path(__file__).resolve().parents[1]
    digest = hashlib.sha256(f"neem-oracle tbox {_CACHE_FORMAT} {sys.version} {onto.cache_key}\0".encode())
    try:
        for name in _CODE:
            digest.update(hashlib.sha256((package / name).read_bytes()).digest())
    except OSError:
        return None
    return digest.hexdigest()[:32]


def _converted(onto: OdbOntology) -> TBox:
    """Built with ``--soma DIR``: the official files as KnowRob's load_owl loads each (its own
    graph, every axiom and annotation, the version marker KnowRob compares; store/owlfile.py)
    and the odb's own axioms in graph ``odb``. Else the ontology's graph (the core extract and
    the odb), as before."""
    source = onto.source
    if source is None or source.soma is None or source.owl is not None:
        return tbox_from_graph(onto.graph)
    from oracle.ontology.generate import generated_graph
    from oracle.ontology.upper import official_files
    from oracle.store.owlfile import tbox_from_file  # rdflib: only a conversion loads it

    own = tbox_from_graph(generated_graph(source.odb, source.mapping), one_graph=True)
    return TBox.combined([*(tbox_from_file(path) for path in official_files(source.soma)), own])


def _plain(tbox: TBox) -> dict[str, Any]:
    """A TBox as JSON-ready lists (a datetime value as ``{"datetime": ISO text}``)."""
    return {"triples": [[s, p, _value(o), graph, since, until] for s, p, o, graph, since, until in tbox.triples],
            "annotations": [[a.s, a.p, _value(a.v)] for a in tbox.annotations],
            "markers": [list(marker) for marker in tbox.markers]}


def _from_plain(data: Any) -> TBox:
    """What ``_plain`` made, each part checked; ValueError/TypeError/KeyError for anything else."""
    triples = []
    for s, p, o, graph, since, until in data["triples"]:
        if not (isinstance(s, str) and isinstance(p, str) and isinstance(graph, str)
                and isinstance(since, (int, float)) and isinstance(until, (int, float))):
            raise ValueError("a triple is not (text, text, value, text, number, number)")
        triples.append(Triple(s, p, _read_value(o), graph, float(since), float(until)))
    annotations = []
    for s, p, v in data["annotations"]:
        if not (isinstance(s, str) and isinstance(p, str)):
            raise ValueError("an annotation's subject or property is not text")
        annotations.append(Annotation(s, p, _read_value(v)))
    markers = []
    for iri, name, version in data["markers"]:
        if not (isinstance(iri, str) and isinstance(name, str) and isinstance(version, str)):
            raise ValueError("a version marker is not three texts")
        markers.append((iri, name, version))
    return TBox(tuple(triples), tuple(annotations), tuple(markers))


def _value(value: Any) -> Any:
    if isinstance(value, datetime):
        return {"datetime": value.isoformat()}
    if isinstance(value, (str, bool, int, float)):
        return value
    raise TypeError(f"a TBox value of type {type(value).__name__} cannot be kept")


def _read_value(value: Any) -> Value:
    if isinstance(value, (str, bool, int, float)):
        return value
    if isinstance(value, dict) and set(value) == {"datetime"} and isinstance(value["datetime"], str):
        return datetime.fromisoformat(value["datetime"])
    raise ValueError("a TBox value is neither text, a number, a boolean nor a datetime")
