"""Consent and ``prior build`` over a store: only consenting NEEMs, k users per count, revocation,
the same tokens the replay counts, on SQLite and on MongoDB (mongomock-ng)."""

from __future__ import annotations

import json

import pytest

from oracle.algorithm.prior import load_prior
from oracle.algorithm.prior_counts import Population, cells_of
from oracle.evaluation.population import sequence_of
from oracle.evaluation.replay import load_users
from oracle.neem.importing import import_chains
from oracle.neem.sharing import build_prior, neem_tokens, set_shared, shared_neems
from oracle.ontology import build_ontology
from oracle.store import open_store
from tests.corpus.harness import run_cli

COMMON = ["pick(apple)", "eat(apple)", "open(fridge)", "pick(red_mug)", "place(red_mug, counter_top)"]


def _chains(path, users=6, days=2):
    rows = []
    for u in range(users):
        minute = 0
        for day in range(days):
            calls = COMMON + (["pick(banana)"] if u == 5 else [])  # only u5 ever picks a banana
            for call in calls:
                rows.append({"user": f"u{u}", "time": f"2026-01-0{day + 1}T08:{minute:02d}:00", "duration": 20,
                             "action": call})
                minute += 1
            minute += 10  # a pause: an idle step between the days' chains
    path.write_text("".join(json.dumps(r) + "\n" for r in rows))
    return path


@pytest.fixture(scope="module")
def onto():
    return build_ontology()


def _sqlite(tmp_path, onto):
    chains = _chains(tmp_path / "c.jsonl")
    store = open_store(tmp_path / "s.sqlite")
    import_chains(store, onto, chains)
    return store, chains


def _cells(prior):
    return {(c, t): n for c, f in prior.tables.items() for t, n in f.items()}


def test_nothing_is_shared_by_default_and_revoking_removes_a_neem(tmp_path, onto):
    store, chains = _sqlite(tmp_path, onto)
    assert shared_neems(store) == []
    assert build_prior(store, onto, 1, None, 3).cells() == 0
    neems = {info.user: info.id for info in store.neems()}
    for neem in neems.values():
        set_shared(store, neem, True)
    everyone = build_prior(store, onto, 1, None, 3)
    assert any("pick(banana)" == t for _, t in _cells(everyone))
    set_shared(store, neems["u5"], False)
    assert neems["u5"] not in {info.id for info in shared_neems(store)}
    rest = build_prior(store, onto, 1, None, 3)
    # u5's counts are gone: the prior is the other five users' counts exactly
    users = load_users(chains)
    others = Population(3)
    for user, rows in users.items():
        if user != "u5":
            others.add(user, [sequence_of(onto, rows)])
    assert _cells(rest) == _cells(others.prior(1))
    assert not any("banana" in t or any("banana" in c for c in context) for context, t in _cells(rest))
    assert _cells(rest) != _cells(everyone)


def test_the_store_names_tasks_as_the_replay_does(tmp_path, onto):
    store, chains = _sqlite(tmp_path, onto)
    users = load_users(chains)
    for info in store.neems():
        assert neem_tokens(store, info.id, onto) == sequence_of(onto, users[info.user])


def test_every_count_written_has_k_users_and_the_cli_round_trip(tmp_path, onto):
    store, chains = _sqlite(tmp_path, onto)
    names = [info.id for info in store.neems()]
    store.close()
    for neem in names:
        assert run_cli(["share", "--store", str(tmp_path / "s.sqlite"), "--neem", neem]).code == 0
    out = tmp_path / "prior.json"
    done = run_cli(["prior", "build", "--store", str(tmp_path / "s.sqlite"), "--k", "6", "--out", str(out)])
    assert done.code == 0, done
    prior = load_prior(out)
    users = load_users(chains)
    per_cell: dict = {}
    for user, rows in users.items():
        for cell in cells_of(sequence_of(onto, rows)):
            per_cell.setdefault(cell, set()).add(user)
    assert prior.cells() > 0
    assert all(len(per_cell[cell]) >= 6 for cell in _cells(prior))  # banana (one user) never
    assert not any("banana" in t for _, t in _cells(prior))
    shown = run_cli(["prior", "show", str(out)])
    assert shown.code == 0 and "k 6" in shown.stdout
    bad = run_cli(["prior", "build", "--store", str(tmp_path / "s.sqlite"), "--k", "0", "--out", str(out)])
    assert bad.code != 0 and "error:" in bad.stderr


@pytest.mark.slow  # mongomock-ng runs the pipeline's $lookups as scans in pure Python: about 10 s a NEEM
@pytest.mark.filterwarnings("ignore:'allowDiskUse'")  # a no-op in mongomock-ng, the real server's large groups need it
def test_mongodb_counts_what_sqlite_counts(tmp_path, onto):
    """One aggregation pipeline on MongoDB (oracle.store.mongo_contexts) over the very documents the
    import wrote: the counts of the SQL statement and of the Python reference over the same NEEMs
    (tests/store/test_mongo_contexts.py: the same on small NEEMs written by hand, unmarked)."""
    import mongomock_ng as mongomock

    from oracle.neem.sharing import count_store, store_cells
    from oracle.store.mongo import MongoStore

    chains = _chains(tmp_path / "c.jsonl", users=2, days=1)
    sqlite = open_store(tmp_path / "s.sqlite")
    import_chains(sqlite, onto, chains)
    mongo = MongoStore(mongomock.MongoClient(), "roslog")
    for info in sqlite.neems():  # the very documents the import wrote (an import into mongomock takes minutes)
        mongo.create_neem(info.id, user=info.user)
        mongo.write_documents(info.id, "triples", sqlite.read_documents(info.id, "triples"))
    for store in (sqlite, mongo):
        for info in store.neems():
            set_shared(store, info.id, True)
    assert _cells(build_prior(mongo, onto, 2, None, 3)) == _cells(build_prior(sqlite, onto, 2, None, 3))
    sums, users = store_cells(mongo, onto, 1, 1, mongo.neems())  # clipped at 1: clipping shows
    reference = count_store(sqlite, onto, 1, sqlite.neems())   # the actions read back, counted in Python
    assert sums == dict(reference.sums) and users == dict(reference.users) and sums


def test_the_sql_count_is_the_count_of_the_tokens_read_back(tmp_path, onto):
    from oracle.neem.sharing import count_store, store_cells

    store, _ = _sqlite(tmp_path, onto)
    infos = store.neems()
    for k in (1, 3):
        sums, users = store_cells(store, onto, 2, k, infos)  # one SQL statement on SQLite
        population = count_store(store, onto, 2, infos)      # the actions read back, counted in Python
        kept = {cell for cell, n in population.users.items() if n >= k}
        assert sums == {cell: population.sums[cell] for cell in kept} and sums
        assert users == {cell: population.users[cell] for cell in kept}
