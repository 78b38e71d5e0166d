"""Consent and the shared prior's counts over a store's NEEMs.

Consent is a field of the NEEM's registry entry (``SHARE_KEY``): ``share`` sets it, ``share
--revoke`` removes it; a NEEM without it is never read by ``prior build`` (nothing is shared by
default), so a revoked NEEM's counts are gone from the next prior built.

``prior build`` reads each consenting NEEM's executed actions in time order (``executed_actions``:
one join the store runs, SQL on SQLite, an aggregation pipeline on MongoDB), names each as the
prior does (``prior.task_key``: the task and its objects' classes; ``idle`` for the idle actions the
logger wrote) and counts the contexts per user (a user's NEEMs together: ``created_by``, a NEEM
without one is its own user), then applies clip, k users and noise (``prior_counts``). Only the
counts leave this module.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

import numpy as np

from oracle.algorithm.prior import IDLE, Prior, task_key
from oracle.algorithm.prior_counts import Population, check_privacy
from oracle.neem.query import executed_actions
from oracle.ontology import OdbOntology
from oracle.store import RDF_TYPE, NeemInfo, Store, TriplePattern, Var

#: the registry field that says a NEEM's aggregates may enter a shared prior
SHARE_KEY = "share_aggregates"


def set_shared(store: Store, neem_id: str, shared: bool) -> NeemInfo:
    """Record (or withdraw) the NEEM's consent in its registry entry."""
    return store.update_meta(neem_id, **{SHARE_KEY: True if shared else None})


def is_shared(info: NeemInfo) -> bool:
    return info.meta.get(SHARE_KEY) is True


def shared_neems(store: Store) -> list[NeemInfo]:
    """The NEEMs whose owners agreed to share aggregates (temporary ones never)."""
    return [info for info in store.neems() if is_shared(info) and not info.temporary]


def neem_tokens(store: Store, neem_id: str, ontology: OdbOntology) -> list[str]:
    """The NEEM's executed actions in time order as the prior names them."""
    objects = {o.iri for o in ontology.objects.values()}
    idle = ontology.vocab.idle_task
    classes: dict[str, str] = {}
    for row in store.match(neem_id, [TriplePattern(Var("O"), RDF_TYPE, Var("C"))]):
        if row["C"] in objects:
            classes.setdefault(row["O"], row["C"])
    tokens = []
    for action in executed_actions(store, neem_id):
        if action.task_class == idle:
            tokens.append(IDLE)
        else:
            tokens.append(task_key(action.task_class, [classes[p] for p in action.participants if p in classes]))
    return tokens


def count_store(store: Store, ontology: OdbOntology, clip: int, neems: Iterable[NeemInfo] | None = None) -> Population:
    """The consenting NEEMs' clipped counts, per user (module docstring)."""
    population = Population(clip)
    by_user: dict[str, list[list[str]]] = {}
    for info in shared_neems(store) if neems is None else neems:
        by_user.setdefault(info.user or f"neem:{info.id}", []).append(neem_tokens(store, info.id, ontology))
    for user, sequences in by_user.items():
        population.add(user, sequences)
    return population


def build_prior(store: Store, ontology: OdbOntology, k: int, epsilon: float | None, clip: int,
                rng: np.random.Generator | None = None) -> Prior:
    """The prior of the store's consenting NEEMs, under the ontology's fingerprint."""
    from oracle.ontology.provenance import fingerprint

    check_privacy(k, epsilon, clip)
    return count_store(store, ontology, clip).prior(k, epsilon, rng, fingerprint(ontology))


def describe(prior: Prior) -> dict[str, Any]:
    """What ``prior show`` prints: the settings, the size, and the largest counts per order."""
    orders: dict[int, list[tuple[float, tuple[str, ...], str]]] = {}
    for context, followers in prior.tables.items():
        for task, count in followers.items():
            orders.setdefault(len(context), []).append((count, context, task))
    return {"fingerprint": prior.fingerprint, "k": prior.k, "epsilon": prior.epsilon, "clip": prior.clip,
            "users": prior.users, "contexts": prior.contexts(), "counts": prior.cells(),
            "orders": {n: sorted(rows, reverse=True) for n, rows in sorted(orders.items())}}


__all__ = ["SHARE_KEY", "build_prior", "count_store", "describe", "is_shared", "neem_tokens", "set_shared",
           "shared_neems"]
