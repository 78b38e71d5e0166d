"""Ontology distance between classes (thesis Algorithm 1, eq. 4.5) and its precomputed matrix.

``dist(A, B) = ln(path(A, B) * CSpec(A, B) + 1)`` with ``CSpec = 1 - depth(lcs) / depth(ontology)``.
With multiple inheritance the least common subsumer (LCS) is the common ancestor that gives the
shortest path A -> LCS -> B; ties go to the deepest (most specific) ancestor, then to the smaller
IRI. Depth is counted in classes along the longest chain from owl:Thing (depth 1). See
docs/ontology.md for why.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING


from oracle.errors import OntologyError
from oracle.files import default_cache_dir, private_folder, prune_cache, used
from oracle.ontology.taxonomy import Taxonomy

if TYPE_CHECKING:  # numpy is imported where a matrix is made: why-not and neems never need one
    import numpy as np

#: Bumped whenever the formula or the tie rules change, so stale caches are never used.
ALGORITHM_VERSION = "alg1-v1"


@dataclass(frozen=True)
class Distance:
    value: float
    lcs: str
    path: int
    cspec: float


def owl_distance(taxonomy: Taxonomy, a: str, b: str) -> Distance:
    """Readable, pair-at-a-time Algorithm 1; the matrix below must agree with it."""
    up_a = taxonomy.ancestors(a)
    up_b = taxonomy.ancestors(b)
    best: tuple[int, int, str] | None = None
    for cls in up_a.keys() & up_b.keys():
        key = (up_a[cls] + up_b[cls], -taxonomy.depth(cls), cls)
        if best is None or key < best:
            best = key
    assert best is not None  # owl:Thing is a common ancestor of every pair
    path, neg_depth, lcs = best
    cspec = 1.0 - (-neg_depth) / taxonomy.max_depth
    return Distance(math.log(path * cspec + 1.0), lcs, path, cspec)


class DistanceMatrix:
    """Distances between all named classes of a taxonomy, indexed by IRI."""

    def __init__(self, classes: tuple[str, ...], values: np.ndarray, lcs: np.ndarray, key: str):
        self.classes = classes
        self.index = {cls: i for i, cls in enumerate(classes)}
        self.values = values
        self.lcs_index = lcs
        self.key = key

    @classmethod
    def from_values(cls, classes: tuple[str, ...], values: np.ndarray) -> DistanceMatrix:
        """A matrix given outright (synthetic worlds in tests and benchmarks); no LCS is known."""
        import numpy as np

        return cls(tuple(classes), values, np.zeros(values.shape, dtype=np.int32), "given")

    def distance(self, a: str, b: str) -> float:
        return float(self.values[self._row(a), self._row(b)])

    def lcs(self, a: str, b: str) -> str:
        return self.classes[int(self.lcs_index[self._row(a), self._row(b)])]

    def _row(self, cls: str) -> int:
        try:
            return self.index[cls]
        except KeyError:
            raise OntologyError(f"unknown class {cls}") from None

    @classmethod
    def compute(cls, taxonomy: Taxonomy) -> DistanceMatrix:
        import numpy as np

        classes = taxonomy.classes
        n = len(classes)
        index = {c: i for i, c in enumerate(classes)}
        max_depth = taxonomy.max_depth
        # Integer key per candidate LCS: shorter path first, then deeper LCS; equal keys keep
        # the earlier (smaller IRI) LCS because candidates are visited in sorted order.
        big = np.iinfo(np.int64).max
        key = np.full((n, n), big, dtype=np.int64)
        lcs = np.zeros((n, n), dtype=np.int32)
        below: dict[str, list[tuple[int, int]]] = {c: [] for c in classes}
        for c in classes:
            for anc, steps in taxonomy.ancestors(c).items():
                below[anc].append((index[c], steps))
        for c in classes:
            members = below[c]
            rows = np.fromiter((m[0] for m in members), dtype=np.int64, count=len(members))
            hops = np.fromiter((m[1] for m in members), dtype=np.int64, count=len(members))
            cand = (hops[:, None] + hops[None, :]) * (max_depth + 1) + (max_depth - taxonomy.depth(c))
            block = np.ix_(rows, rows)
            current = key[block]
            better = cand < current
            key[block] = np.where(better, cand, current)
            lcs[block] = np.where(better, index[c], lcs[block])
        path = key // (max_depth + 1)
        depth_lcs = max_depth - key % (max_depth + 1)
        cspec = 1.0 - depth_lcs / max_depth
        values = np.log(path * cspec + 1.0)
        return cls(classes, values, lcs, taxonomy_key(taxonomy))

    @classmethod
    def cached(cls, taxonomy: Taxonomy, cache_dir: Path | None = None) -> DistanceMatrix:
        """Load the matrix for this taxonomy from the cache, computing and saving it if absent."""
        import numpy as np

        directory = cache_dir if cache_dir is not None else default_cache_dir()
        key = taxonomy_key(taxonomy)
        path = directory / f"distances-{key}.npz"
        if path.exists():
            try:
                with np.load(path, allow_pickle=False) as data:
                    classes = tuple(str(c) for c in data["classes"])
                    if classes == taxonomy.classes:
                        used(path)
                        return cls(classes, data["values"], data["lcs"], key)
            except (OSError, ValueError, KeyError):
                pass  # a damaged cache file is recomputed below
        matrix = cls.compute(taxonomy)
        try:
            private_folder(directory)  # each missing folder 0700 whatever the umask
            tmp = path.with_name(path.name + f".{os.getpid()}.tmp.npz")
            np.savez_compressed(tmp, classes=np.array(matrix.classes), values=matrix.values, lcs=matrix.lcs_index)
            os.chmod(tmp, 0o600)  # the cache is the user's, like the stores
            os.replace(tmp, path)
            prune_cache(directory, "distances-*.npz")
        except OSError:
            pass  # caching is an optimisation; a read-only home still works
        return matrix


def taxonomy_key(taxonomy: Taxonomy) -> str:
    table = {c: list(taxonomy.parents(c)) for c in taxonomy.classes}
    blob = json.dumps([ALGORITHM_VERSION, table], sort_keys=True).encode()
    return hashlib.sha256(blob).hexdigest()[:24]


