"""KnowRob 2.x's own tests for the mirrored predicates (restated in prolog/compat/knowrob_2x.plt)
and the new KnowRob features on the Python stores: fact scopes bound to free intervals,
load_owl/1 and annotations, on SQLite and on the Mongo code path (mongomock-ng)."""

from __future__ import annotations

import itertools
import re
import shutil
import subprocess

import pytest

from oracle.bridge import Bridge
from oracle.paths import prolog_dir
from oracle.store import open_store
from oracle.store.mongo import MongoStore

ADAPTER = prolog_dir() / "compat" / "knowrob_2x.pl"
SUITE = prolog_dir() / "compat" / "knowrob_2x.plt"


def run_knowrob_suite() -> tuple[int, int]:
    """(passed, total) of the restated KnowRob 2.x tests on the memory backend (plain swipl)."""
    goal = (f"load_files(['{ADAPTER}'],[]), load_files(['{SUITE}'],[]), knowrob_2x_units(U), "
            "knowrob_2x_score(U, P, T), format('score ~w ~w~n', [P, T])")
    done = subprocess.run(["swipl", "-g", goal, "-t", "halt"], capture_output=True, text=True, timeout=300)
    found = re.search(r"^score (\d+) (\d+)$", done.stdout, re.M)
    assert found, done.stdout[-2000:] + done.stderr[-2000:]
    return int(found.group(1)), int(found.group(2))


@pytest.mark.skipif(shutil.which("swipl") is None, reason="needs swipl")
def test_knowrob_2x_own_tests_pass():
    # the 60 of the mirrored predicates and lang/scope's 13, but the one KnowRob marks fixme and
    # the one it marks blocked: they run here, and are not counted as passes
    assert run_knowrob_suite() == (71, 71)


def _sqlite(tmp_path):
    return open_store(tmp_path / "k.sqlite")


def _mongomock(_):
    import mongomock_ng

    return MongoStore(mongomock_ng.MongoClient(), "k2x")


@pytest.fixture(params=[_sqlite, _mongomock], ids=["sqlite", "mongomock"])
def bridge(request, tmp_path):
    store = request.param(tmp_path)
    store.create_neem("k")
    b = Bridge(store, "k")
    yield b
    b.close()
    store.close()


FAMILY = prolog_dir() / "fixtures" / "knowrob_2x" / "family.ttl"
SWRL = "http://knowrob.org/kb/swrl_test#"


def test_load_owl_and_annotations(bridge):
    bridge.query(f"load_owl('{FAMILY}')")
    rows = bridge.solutions(f"triple(X, transitive('{SWRL}isParentOf'), '{SWRL}Lea')", ["X"])
    assert sorted(rows) == [(f"{SWRL}Fred",), (f"{SWRL}Rex",)]
    # the class closure comes from the store: Man is a TestThing
    assert bridge.solutions(f"instance_of('{SWRL}Rex', '{SWRL}TestThing')", []) == [()]
    assert bridge.solutions(f"has_label('{SWRL}Adult', L)", ["L"]) == [("adult",)]
    assert bridge.solutions(f"triple('{SWRL}RectangleSmall', '{SWRL}hasHeightInMeters', H)", ["H"]) == [(6,)]
    # labels and comments are annotations, not triples
    assert bridge.solutions(f"triple('{SWRL}Adult', rdfs:label, _)", []) == []


def test_free_interval_bound_to_fact_scope(bridge):
    bridge.query(f"kb_project(triple('{SWRL}Lea', '{SWRL}hasNumber', '+4934') during [10, 34])")
    rows = bridge.solutions(f"triple('{SWRL}Lea', '{SWRL}hasNumber', '+4934') during [S, U]", ["S", "U"])
    assert rows == [(10.0, 34.0)]
    assert bridge.solutions(f"triple('{SWRL}Lea', '{SWRL}hasNumber', '+4934') during [14, 24]", []) == [()]
    assert bridge.solutions(f"triple('{SWRL}Lea', '{SWRL}hasNumber', '+4934') during [5, 24]", []) == []
    rows = bridge.solutions(f"kb_call(triple('{SWRL}Lea', P, O), dict{{}}, F), get_dict(time, F, T), "
                            "get_dict(until, T, U)", ["O", "U"])
    assert rows == [("+4934", 34.0)]


def test_knowrob_2x_own_tests_on_the_python_stores(bridge):
    """The same tests with every unit on a fresh NEEM of the store (SQLite, mongomock-ng)."""
    from pyswip import Atom, Prolog

    ids = itertools.count(1)

    def py_fresh_neem(out):
        neem = f"k2x{next(ids)}"
        bridge.store.create_neem(neem)
        out.unify(Atom(neem))
        return True

    Prolog.register_foreign(py_fresh_neem, arity=1, module="neem_store")
    bridge.query(f"load_files(['{ADAPTER}'],[]), load_files(['{SUITE}'],[])")
    bridge.query("retractall(knowrob_2x:fresh_store_hook), "
                 "assertz((knowrob_2x:fresh_store_hook :- neem_store:py_fresh_neem(Id), store_use_python(Id)))")
    try:
        (row,) = bridge.query("knowrob_2x_units(U), knowrob_2x_score(U, P, T), "
                              "findall(N, (member(X, U), plunit:failed(X, N, _, _)), F)")
    finally:
        bridge.query("retractall(knowrob_2x:fresh_store_hook)")
    failed = {name.decode() if isinstance(name, bytes) else str(name) for name in row["F"]}
    print(f"KnowRob 2.x tests on {type(bridge.store).__name__}: {row['P']}/{row['T']}, failed: {sorted(failed)}")
    assert row["T"] == 71  # KnowRob's fixme and blocked tests not counted
    assert failed == set()  # merging, narrowing and deleting included (store.project)
    assert row["P"] == 71


def test_kb_project_merges_narrows_and_unprojects_in_the_store(bridge):
    """kb_project's union, until's narrowing and kb_unproject reach the stored documents (one
    document per fact, its scope changed in place), not only the answers."""
    fact = f"triple('{SWRL}Lea', '{SWRL}hasNumber', '+4934')"

    def stored() -> list[tuple[float, float]]:
        docs = bridge.store.find("k", f"{SWRL}Lea", f"{SWRL}hasNumber", "+4934", exact=True)
        return sorted((float(str(d["scope"]["time"]["since"])), float(str(d["scope"]["time"]["until"]))) for d in docs)

    bridge.query(f"kb_project({fact} during [10, 20])")
    bridge.query(f"kb_project({fact} during [15, 34])")
    assert stored() == [(10.0, 34.0)]
    bridge.query(f"kb_project({fact} until 30)")
    assert stored() == [(10.0, 30.0)]
    bridge.query(f"kb_project({fact} during [50, 60])")
    assert stored() == [(10.0, 30.0), (50.0, 60.0)]
    bridge.query(f"kb_unproject(triple('{SWRL}Lea', '{SWRL}hasNumber', _))")
    assert stored() == [] and bridge.solutions(f"{fact} during [S, U]", ["S", "U"]) == []
