"""The bridge on a NEEM written by the logger: KnowRob queries, answers, values as data."""

from __future__ import annotations

from datetime import datetime, timezone

import pytest

from oracle import bridge as bridge_module
from oracle.bridge import Bridge, term_text
from oracle.errors import PrologError, StoreError
from oracle.store import Triple, open_store


def ts(h: int, m: int = 0) -> float:
    return datetime(2024, 5, 1, h, m, tzinfo=timezone.utc).timestamp()


def test_knowrob_query_on_logged_neem(sqlite_bridge):
    rows = sqlite_bridge.solutions(
        "is_action(A), executes_task(A, T), instance_of(T, odb:pour), has_participant(A, O),"
        " event_interval(A, B, E)", ["A", "O", "B", "E"])
    objects = sorted(o.rsplit("#", 1)[1] for _, o, _, _ in rows)
    assert "Object_thermos" in objects and "Object_green_mug" in objects
    assert {(b, e) for _, _, b, e in rows} == {(ts(8, 1), ts(8, 3))}
    assert all(isinstance(b, float) for _, _, b, _ in rows)


def test_roles_and_time_of_day(sqlite_bridge):
    rows = sqlite_bridge.query(
        "once((executes_task(A, T), instance_of(T, odb:pour))),"
        " findall(R, (has_role(_, R) during A, task_role(T, R)), Rs),"
        " findall(R, (has_role(_, R), task_role(T, R)), Now),"
        " event_time_of_day(A, Part)")
    # the roles classify their objects during the action only (KnowRob's has_role(O, R) during A)
    assert len(rows[0]["Rs"]) == 2 and rows[0]["Now"] == [] and rows[0]["Part"] == "Morning"


def test_why_not_ranked_lower_and_user_choice(sqlite_bridge):
    answer = sqlite_bridge.why_not("pick", ["apple"], ts(8, 2))
    kinds = [r["reason"] for r in answer["reasons"]]
    assert kinds[:2] == ["ranked_lower", "user_chose"]
    lower = answer["reasons"][0]
    assert lower["rank"] == 2 and lower["higher"][0]["task"] == "pour(thermos, green_mug)"
    assert {"reason": "done_later", "task": "pick(apple)", "time": ts(12, 1)} in answer["reasons"]


def test_why_not_object_not_perceived_then(sqlite_bridge):
    answer = sqlite_bridge.why_not("pick", ["banana"], ts(12, 30))
    assert answer["reasons"][0]["why"] == "object_not_perceived"
    assert answer["reasons"][0]["object"] == "banana"


def test_what_next_and_something_else(sqlite_bridge):
    chain = sqlite_bridge.what_next()["chain"]
    assert [c["task"] for c in chain] == ["pick(apple)", "pour(thermos, green_mug)"]
    alt = sqlite_bridge.something_else()
    assert alt["current"] == "pick(apple)" and alt["alternatives"][0]["task"] == "pour(thermos, green_mug)"
    alt = sqlite_bridge.something_else("pour", ["thermos", "green_mug"])
    assert alt["alternatives"][0]["task"] == "pick(apple)"


def test_compiled_conjunction_is_one_crossing(sqlite_bridge):
    goal = ("executes_task(A, T), has_time_interval(A, I), has_interval_begin(I, B),"
            " has_interval_end(I, E), has_participant(A, O)")
    before = bridge_module.CROSSINGS["py_match"]
    compiled = sqlite_bridge.solutions(goal, ["A", "T", "B", "E", "O"])
    one = bridge_module.CROSSINGS["py_match"] - before
    before = bridge_module.CROSSINGS["py_match"]
    stepwise = sqlite_bridge.solutions(goal, ["A", "T", "B", "E", "O"], stepwise=True)
    assert one == 1 and bridge_module.CROSSINGS["py_match"] - before > 1
    assert sorted(compiled) == sorted(stepwise) and compiled


def test_kb_group_is_findall_grouped_and_one_crossing(sqlite_bridge):
    goal = "( executes_task(A, T), has_participant(A, O) )"
    before = bridge_module.CROSSINGS["py_match"]
    grouped = sqlite_bridge.query(f"kb_query:kb_group(A-T, O, {goal}, any, G)")[0]["G"]
    assert bridge_module.CROSSINGS["py_match"] - before == 1
    expected = sqlite_bridge.query(f"findall((A-T)-O, kb_call({goal}, any), P), msort(P, S), group_pairs_by_key(S, G)")
    assert grouped == expected[0]["G"] and any("," in str(group) for group in grouped)


@pytest.mark.parametrize("name", ["it's", 'a "quoted" name', "x), halt, (y", "spa ce", "ünïcødé ✓", "back\\slash\nnl"])
def test_names_are_data(tmp_path, name):
    store = open_store(tmp_path / "s.sqlite")
    store.create_neem("n1")
    store.insert("n1", [Triple(name, "http://e.org/p", name), Triple(name, "http://e.org/n", 2.5)])
    bridge = Bridge(store, "n1")
    try:
        rows = bridge.solutions("triple(S, 'http://e.org/p', O), triple(S, 'http://e.org/n', N)", ["S", "O", "N"])
        assert rows == [(name, name, 2.5)]
        # and the same name going Prolog -> Python -> store as a constant
        bridge.query("kb_project(triple('http://e.org/s', 'http://e.org/q', 'x'))")
        assert bridge.solutions("triple(S, 'http://e.org/q', x)", ["S"]) == [("http://e.org/s",)]
    finally:
        bridge.close()


def test_term_text_numbers():
    assert term_text(float("inf")) == "1.0Inf" and term_text(1e20) == "1.0e+20" and term_text(True) == "true"


def test_store_error_becomes_prolog_error(tmp_path):
    store = open_store(tmp_path / "s.sqlite")
    store.create_neem("n1")
    bridge = Bridge(store, "n1")
    try:
        store.drop_neem("n1")
        with pytest.raises(PrologError, match="n1"):
            bridge.query("triple(S, P, O)")
    finally:
        bridge.close()


def test_unknown_neem(tmp_path):
    store = open_store(tmp_path / "s.sqlite")
    with pytest.raises(StoreError):
        Bridge(store, "nope")
