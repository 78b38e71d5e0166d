"""The shared prior's aggregation pipeline on MongoDB counts what the SQL statement on SQLite counts
and what the Python reference (prior_counts.Population over the token sequences) counts, on NEEMs
written by hand to hold each rule's edge: ties in time, two and three objects, idle steps, actions
that are not counted, two NEEMs of one user, begins as Decimal128 and as doubles."""

from __future__ import annotations

import warnings

import pytest
from bson.decimal128 import Decimal128

from oracle.algorithm.prior_counts import Population
from oracle.neem import terms as T
from oracle.store import RDF_TYPE
from oracle.store.mongo import MongoStore
from oracle.store.mongo_contexts import count_cells as mongo_cells
from oracle.store.mongo_contexts import pipeline
from oracle.store.sqlite import SQLiteStore
from oracle.store.sqlite.contexts import count_cells as sql_cells

N = "urn:x#"
TASKS = {f"{N}pick": "pick", f"{N}place": "place", f"{N}stack": "stack", f"{N}eat": "eat", f"{N}Idle": "idle",
         f"{N}dollar": "$tok"}
OBJECTS = {f"{N}mug": "mug", f"{N}counter": "counter", f"{N}apple": "apple", f"{N}plate": "plate",
           f"{N}other_mug": "mug"}  # two classes one name: one token, as local names give it


def _neem(actions, decimal=True):
    """Triples of actions ``(iri, task class, begin, object classes)``; a task class None: an action
    whose task is of no known class; ``iri`` ending in '!': not typed dul:Action."""
    docs = []
    for iri, task_class, begin, objects in actions:
        a, t, i = f"{N}{iri.rstrip('!')}", f"{N}{iri.rstrip('!')}_task", f"{N}{iri.rstrip('!')}_interval"
        docs += [{"s": a, "p": T.EXECUTES, "o": t},
                 {"s": t, "p": RDF_TYPE, "o": f"{N}{task_class}" if task_class else f"{N}Unknown"},
                 {"s": t, "p": RDF_TYPE, "o": "http://www.w3.org/2002/07/owl#NamedIndividual"},
                 {"s": a, "p": RDF_TYPE, "o": T.ACTION if not iri.endswith("!") else f"{N}PhysicalAction"},
                 {"s": a, "p": T.HAS_INTERVAL, "o": i},
                 {"s": i, "p": T.BEGIN, "o": Decimal128(str(begin)) if decimal else float(begin)},
                 {"s": a, "p": T.PERFORMED_BY, "o": f"{N}robot"}]  # fmt: skip
        for n, cls in enumerate(objects):
            thing = f"{N}{iri.rstrip('!')}_o{n}"
            docs += [{"s": a, "p": T.PARTICIPANT, "o": thing}, {"s": thing, "p": RDF_TYPE, "o": f"{N}{cls}"}]
        docs += [{"s": a, "p": T.PARTICIPANT, "o": f"{N}robot"}]
    docs.append({"s": f"{N}robot", "p": RDF_TYPE, "o": f"{N}Robot"})  # a participant of no object class
    return docs


#: (NEEM, user, actions, begins as Decimal128) and the tokens each NEEM gives, in order
NEEMS = [
    ("n1", "ann", [("a3", "pick", 30, ["mug"]), ("a1", "pick", 10, ["mug"]), ("a2", "eat", 20, ["apple"]),
                   ("a4", "place", 40, ["mug", "counter"]), ("a5", "Idle", 50, []), ("a6", "pick", 60, ["mug"]),
                   ("a7", "eat", 70, ["apple"])], True),
    # ties in time: by IRI ("b1" < "b2"); an action of an unknown task and one not typed dul:Action: not counted
    ("n2", "ann", [("b2", "eat", 10, ["apple"]), ("b1", "pick", 10, ["mug"]), ("b3", None, 15, []),
                   ("b4!", "pick", 16, ["mug"]), ("b5", "pick", 20, ["other_mug"])], False),
    ("n3", "bob", [("c1", "pick", 1.5, ["mug"]), ("c2", "eat", 2.25, ["apple"]),
                   ("c3", "stack", 3, ["plate", "mug", "counter"]), ("c4", "Idle", 4, []),
                   ("c5", "pick", 5, ["mug"]), ("c6", "dollar", 6, [])], True),
    ("n4", "$cy", [("d1", "pick", 100, ["mug"]), ("d2", "eat", 200, ["apple"]), ("d3", "pick", 300, ["mug"]),
                   ("d4", "eat", 400, ["apple"]), ("d5", "pick", 500, ["mug"])], True),
]  # fmt: skip
TOKENS = {
    "n1": ["pick(mug)", "eat(apple)", "pick(mug)", "place(counter,mug)", "idle", "pick(mug)", "eat(apple)"],
    "n2": ["pick(mug)", "eat(apple)", "pick(mug)"],
    "n3": ["pick(mug)", "eat(apple)", "stack(counter,plate)", "idle", "pick(mug)", "$tok"],  # SQL's MIN and MAX
    "n4": ["pick(mug)", "eat(apple)", "pick(mug)", "eat(apple)", "pick(mug)"],
}


def _stores(tmp_path):
    mongomock_ng = pytest.importorskip("mongomock_ng")
    stores = [SQLiteStore(tmp_path / "s.sqlite"), MongoStore(mongomock_ng.MongoClient(), "roslog")]
    for store in stores:
        for neem, user, actions, decimal in NEEMS:
            store.create_neem(neem, user=user)
            store.write_documents(neem, "triples", _neem(actions, decimal))
    return stores


def _reference(clip, k):
    population = Population(clip)
    for user in ("ann", "bob", "$cy"):
        population.add(user, [TOKENS[neem] for neem, u, _, _ in NEEMS if u == user])
    return sorted((c, t, float(population.sums[(c, t)]), n) for (c, t), n in population.users.items() if n >= k)


def _mongo(store, neems, clip, k):
    with warnings.catch_warnings():  # mongomock-ng says allowDiskUse (for a real server's large groups) is a no-op
        warnings.simplefilter("ignore", UserWarning)
        return sorted(mongo_cells(store, neems, TASKS, OBJECTS, clip, k))


@pytest.mark.parametrize(("clip", "k"), [(1, 1), (2, 1), (3, 2), (9, 3)])
def test_the_pipeline_counts_what_the_sql_statement_and_the_reference_count(tmp_path, clip, k):
    sqlite, mongo = _stores(tmp_path)
    neems = [(neem, user) for neem, user, _, _ in NEEMS]
    expected = _reference(clip, k)
    assert expected  # every setting keeps some counts
    assert sorted(sql_cells(sqlite, neems, TASKS, OBJECTS, clip, k)) == expected
    assert _mongo(mongo, neems, clip, k) == expected


def test_the_pipeline_keeps_a_cell_only_with_k_users_and_never_crosses_neems(tmp_path):
    _, mongo = _stores(tmp_path)
    rows = _mongo(mongo, [(neem, user) for neem, user, _, _ in NEEMS], 3, 3)
    assert rows and all(users >= 3 for *_, users in rows)
    everyone = {(c, t) for c, t, _, _ in _mongo(mongo, [(neem, user) for neem, user, _, _ in NEEMS], 3, 1)}
    assert (("pick(mug)", "eat(apple)", "pick(mug)"), "place(counter,mug)") in everyone
    assert (("idle", "pick(mug)"), "eat(apple)") in everyone and not any(t == "idle" for _, t in everyone)
    # n1 ends idle, pick(mug), eat(apple) and n2 (same user) starts with pick(mug): never one sequence
    assert (("idle", "pick(mug)", "eat(apple)"), "pick(mug)") not in everyone


def test_one_aggregation_over_every_neem_and_nothing_of_a_name_is_an_expression():
    start, stages = pipeline([("n1", "ann"), ("n2", "$cy")], TASKS, OBJECTS, 3, 5)
    assert start == "n1_triples"
    assert [s["$unionWith"]["coll"] for s in stages if "$unionWith" in s] == ["n2_triples"]
    assert any("$setWindowFields" in s for s in stages)
    union = next(s["$unionWith"]["pipeline"] for s in stages if "$unionWith" in s)
    assert {"$literal": "$cy"} in [s["$project"]["usr"] for s in union if "$project" in s]


def test_no_neem_no_aggregation(tmp_path):
    _, mongo = _stores(tmp_path)
    assert mongo_cells(mongo, [], TASKS, OBJECTS, 3, 1) == []


def test_a_begin_that_is_no_number_is_a_store_error_not_a_traceback(tmp_path):
    from oracle.errors import StoreError

    _, mongo = _stores(tmp_path)
    mongo.write_documents("n4", "triples", [{"s": f"{N}d1_interval", "p": T.BEGIN, "o": "soon"}])
    with pytest.raises(StoreError, match="cannot count the shared prior"):
        _mongo(mongo, [("n4", "$cy")], 3, 1)


def test_a_real_mongod_counts_the_same(tmp_path):
    """What mongomock-ng cannot show (the server's own $setWindowFields, $shift over a compound sort,
    $unionWith with $lookup inside, numeric comparison across BSON types): runs when NEEM_MONGO_URI
    names a MongoDB >= 5.0, else skips with that reason."""
    from tests.store.conftest import make_store

    mongo = make_store("mongodb", tmp_path)  # skips: no MongoDB server at NEEM_MONGO_URI
    try:
        for neem, user, actions, decimal in NEEMS:
            mongo.create_neem(neem, user=user)
            mongo.write_documents(neem, "triples", _neem(actions, decimal))
        neems = [(neem, user) for neem, user, _, _ in NEEMS]
        for clip, k in ((1, 1), (3, 2)):
            assert sorted(mongo_cells(mongo, neems, TASKS, OBJECTS, clip, k)) == _reference(clip, k)
    finally:
        mongo._test_cleanup()
        mongo.close()
