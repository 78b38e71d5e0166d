"""The shared prior: what other people usually do next, as counts of task contexts.

A ``Prior`` is read-only and loaded once per process from a small versioned JSON file
(``python -m oracle prior build``): for each context of the last 0-3 tasks (idle steps as the
replay has them, the token ``idle``), the counts of the task that followed, summed over the
consenting users, each count kept only when at least ``k`` different users contributed to it,
optionally with Laplace noise (``epsilon``). A task is named by ``task_key``: the task's local name
and its objects' local names, sorted (the same key a NEEM's triples and a replay's options give).
It holds counts only: never a sequence, a time or a user id.

``Prior.probabilities`` is PPM-C without exclusion over those counts (the ``ngram`` baseline's rule,
docs/evaluation.md): the order-0 share backed off to uniform over the offer, then each longer
context found blends in its followers with escape ``kinds / (seen + kinds)``. docs/algorithm.md,
"Shared prior".
"""

from __future__ import annotations

import hashlib
import json
import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from oracle.algorithm.records import Option, local_name
from oracle.errors import NeemOracleError
from oracle.files import write_private_bytes

FORMAT = "neem-oracle-prior"
VERSION = 1
#: the longest context counted (orders 0 .. MAX_ORDER)
MAX_ORDER = 3
#: the token of an idle step (a chain delimiter; counted as context, never as a task that followed)
IDLE = "idle"
#: the product's anonymity threshold and clipping (docs/algorithm.md, "Privacy")
DEFAULT_K = 5
DEFAULT_CLIP = 3

Context = tuple[str, ...]


class PriorError(NeemOracleError):
    """A prior file is missing, malformed, of another version or of another ontology."""


def task_key(task: str, objects: Iterable[str | None] = ()) -> str:
    """The name a prior counts a task by: ``take(bowl)``, objects by local name, sorted (a NEEM's
    participants carry no role order, an Option's do: sorting makes both give one key)."""
    names = sorted(local_name(o) for o in objects if o is not None)
    return f"{local_name(task)}({','.join(names)})" if names else local_name(task)


def option_key(option: Option) -> str:
    return task_key(option.task, (option.target, option.reference))


@dataclass(frozen=True)
class Prior:
    """Follower counts per context (module docstring); ``tables[context][task] = count``."""

    tables: Mapping[Context, Mapping[str, float]]
    fingerprint: str | None = None
    k: int = DEFAULT_K
    epsilon: float | None = None
    clip: int = DEFAULT_CLIP
    users: int | None = None  # how many users were counted (a total, not who)
    _totals: dict[Context, tuple[float, int]] = field(default_factory=dict, repr=False, compare=False)
    _digest: list[str] = field(default_factory=list, repr=False, compare=False)

    def __post_init__(self) -> None:
        for context, followers in self.tables.items():
            self._totals[context] = (float(sum(followers.values())), len(followers))

    def probabilities(self, context: Sequence[str], candidates: Sequence[str]) -> tuple[np.ndarray, np.ndarray]:
        """P(candidate | the latest tokens of ``context``) backed off PPM-C-style over orders 3..0,
        and the order-0 share alone (each backed off to uniform over the candidates)."""
        size = len(candidates)
        probs = np.full(size, 1.0 / size if size else 0.0)
        unigram = probs
        for n in range(0, min(MAX_ORDER, len(context)) + 1):
            key = tuple(context[len(context) - n:])
            followers = self.tables.get(key)
            if not followers:
                continue  # an unseen context: the shorter one stands (as the ngram baseline)
            seen, kinds = self._totals[key]
            counts = np.array([followers.get(c, 0.0) for c in candidates])
            probs = (counts + kinds * probs) / (seen + kinds)
            if n == 0:
                unigram = probs
        return probs, unigram

    def contexts(self) -> int:
        return len(self.tables)

    def cells(self) -> int:
        return sum(len(f) for f in self.tables.values())

    # -- the file ----------------------------------------------------------------------------
    def to_json(self) -> dict[str, Any]:
        rows = [{"context": list(context), "next": dict(sorted(followers.items()))}
                for context, followers in sorted(self.tables.items(), key=lambda item: (len(item[0]), item[0]))]
        return {"format": FORMAT, "version": VERSION, "fingerprint": self.fingerprint, "k": self.k,
                "epsilon": self.epsilon, "clip": self.clip, "users": self.users, "max_order": MAX_ORDER,
                "idle": IDLE, "contexts": rows}

    @staticmethod
    def from_json(data: Any, source: str = "prior") -> Prior:
        if not isinstance(data, dict) or data.get("format") != FORMAT:
            raise PriorError(f"{source}: not a neem-oracle prior (no format {FORMAT!r})")
        if data.get("version") != VERSION:
            raise PriorError(f"{source}: prior version {data.get('version')!r}, this program reads {VERSION}")
        tables: dict[Context, dict[str, float]] = {}
        try:
            for row in data["contexts"]:
                context = tuple(row["context"])
                if len(context) > MAX_ORDER or not all(isinstance(t, str) for t in context):
                    raise ValueError(f"bad context {row['context']!r}")
                followers = {str(t): float(n) for t, n in row["next"].items()}
                if any(not math.isfinite(n) or n < 0 for n in followers.values()):
                    raise ValueError(f"bad count in context {list(context)!r}")
                tables[context] = followers
            k, epsilon, clip = int(data["k"]), data.get("epsilon"), int(data.get("clip", DEFAULT_CLIP))
            epsilon = None if epsilon is None else float(epsilon)
            fingerprint = data.get("fingerprint")
            users = data.get("users")
        except (KeyError, TypeError, ValueError, AttributeError) as error:
            raise PriorError(f"{source}: malformed prior ({error})") from None
        return Prior(tables, None if fingerprint is None else str(fingerprint), k, epsilon, clip,
                     None if users is None else int(users))

    def digest(self) -> str:
        """A digest of what the prior holds: a fit learnt with it is kept under it (oracle.fitcache)."""
        if not self._digest:
            text = json.dumps(self.to_json(), sort_keys=True, separators=(",", ":"))
            self._digest.append(hashlib.sha256(text.encode()).hexdigest())
        return self._digest[0]

    def save(self, path: Path | str) -> None:
        text = json.dumps(self.to_json(), indent=0, sort_keys=False) + "\n"
        try:
            write_private_bytes(path, text.encode("utf-8"))  # 0600 whatever the umask, written aside and moved
        except OSError as error:
            raise PriorError(f"{path}: cannot write ({error.strerror})") from None


def load_prior(path: Path | str, fingerprint: str | None = None) -> Prior:
    """The prior of a file; PriorError when it is unreadable, malformed, or counted under an
    ontology other than ``fingerprint`` (when both are known)."""
    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
    except OSError as error:
        raise PriorError(f"{path}: cannot read ({error.strerror})") from None
    except ValueError as error:
        raise PriorError(f"{path}: not JSON ({error})") from None
    prior = Prior.from_json(data, str(path))
    if fingerprint is not None and prior.fingerprint is not None and prior.fingerprint != fingerprint:
        raise PriorError(f"{path}: counted under another ontology (fingerprint {prior.fingerprint[:12]}, "
                         f"this one {fingerprint[:12]})")
    return prior


def store_prior_path(location: str) -> Path | None:
    """Where a store's own prior lives: ``PATH.prior.json`` beside a SQLite file (None for a server)."""
    if "://" in location and not location.startswith("sqlite://"):
        return None
    return Path(location.removeprefix("sqlite://") + ".prior.json")


def find_prior(given: str | None, location: str, ontology: Any = None) -> Prior | None:
    """The prior ``--prior`` names ('none': none), else the store's own if it has one; checked
    against ``ontology``'s fingerprint."""
    if given == "none":
        return None
    fingerprint = None
    if ontology is not None:
        from oracle.ontology.provenance import fingerprint as of

        fingerprint = of(ontology)
    if given is not None:
        return load_prior(given, fingerprint)
    own = store_prior_path(location)
    return load_prior(own, fingerprint) if own is not None and own.is_file() else None


__all__ = ["DEFAULT_CLIP", "DEFAULT_K", "FORMAT", "IDLE", "MAX_ORDER", "VERSION", "Context", "Prior", "PriorError",
           "find_prior", "load_prior", "option_key", "store_prior_path", "task_key"]
