"""Consent and the shared prior's counts over a store's NEEMs.

Consent is a field of the NEEM's registry entry (``SHARE_KEY``): ``share`` sets it, ``share
--revoke`` removes it; a NEEM without it is never read by ``prior build`` (nothing is shared by
default), so a revoked NEEM's counts are gone from the next prior built.

``prior build`` counts, over the consenting NEEMs, each task after each context of the 0-3 tasks
before it, named as the prior names them (``prior.task_key``: the task and its objects' classes;
``idle`` for the idle actions the logger wrote), per user (a user's NEEMs together: ``created_by``;
a NEEM without one is its own user), clipped, and keeps the counts of >= k users: on SQLite all of
it in one SQL statement (oracle.store.sqlite.contexts), on MongoDB in one aggregation pipeline
(oracle.store.mongo_contexts, the same rules); ``count_store`` reads each NEEM's executed actions in
time order and counts them here (the reference both are tested against). Then the noise
(``prior_counts.released``). Only the counts leave this module.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any

import numpy as np

from oracle.algorithm.prior import IDLE, Prior, task_key
from oracle.algorithm.records import local_name
from oracle.algorithm.prior_counts import Cell, Population, check_privacy, released
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
    """The consenting NEEMs' clipped counts, per user, read in Python (module docstring)."""
    population = Population(clip)
    by_user: dict[str, list[list[str]]] = {}
    for info in shared_neems(store) if neems is None else neems:
        by_user.setdefault(user_of(info), []).append(neem_tokens(store, info.id, ontology))
    for user, sequences in by_user.items():
        population.add(user, sequences)
    return population


def user_of(info: NeemInfo) -> str:
    """Who a NEEM's counts are clipped and counted as: its user, or the NEEM alone without one."""
    return info.user or f"neem:{info.id}"


def store_cells(store: Store, ontology: OdbOntology, clip: int, k: int,
                neems: Sequence[NeemInfo]) -> tuple[dict[Cell, float], dict[Cell, int]]:
    """The clipped sums and user counts of the cells at least ``k`` users gave: on SQLite in one SQL
    statement (oracle.store.sqlite.contexts), on MongoDB in one aggregation pipeline
    (oracle.store.mongo_contexts), elsewhere from each NEEM's actions as the store's join reads them."""
    from oracle.store import mongo_contexts
    from oracle.store.mongo import MongoStore
    from oracle.store.sqlite import SQLiteStore, contexts

    count_cells = (contexts.count_cells if isinstance(store, SQLiteStore)
                   else mongo_contexts.count_cells if isinstance(store, MongoStore) else None)
    if count_cells is not None:
        tasks = {t.iri: local_name(t.iri) for t in ontology.tasks.values()}
        tasks[ontology.vocab.idle_task] = IDLE
        objects = {o.iri: local_name(o.iri) for o in ontology.objects.values()}
        rows = count_cells(store, [(info.id, user_of(info)) for info in neems], tasks, objects, clip, k)
        return ({(c, t): n for c, t, n, _ in rows}, {(c, t): u for c, t, _, u in rows})
    population = count_store(store, ontology, clip, neems)
    return dict(population.sums), dict(population.users)


def build_prior(store: Store, ontology: OdbOntology, k: int, epsilon: float | None, clip: int,
                rng: np.random.Generator | None = None, neems: Sequence[NeemInfo] | None = None) -> Prior:
    """The prior of the store's consenting NEEMs, under the ontology's fingerprint."""
    from oracle.ontology.provenance import fingerprint

    check_privacy(k, epsilon, clip)
    chosen = shared_neems(store) if neems is None else list(neems)
    sums, users = store_cells(store, ontology, clip, k, chosen)
    return Prior(released(sums, users, k, epsilon, clip, rng), fingerprint(ontology), k, epsilon, clip,
                 len({user_of(info) for info in chosen}))


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
           "shared_neems", "store_cells", "user_of"]
