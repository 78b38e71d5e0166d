"""The bridge on a NEEM written by the logger: KnowRob queries, answers, values as data."""

from __future__ import annotations

from datetime import datetime, timezone

import pytest

from oracle import bridge as bridge_module
from oracle.bridge import Bridge, quote_atom, term_text
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


def test_why_not_times_of_a_call_done_often(tmp_path, onto):
    """done / done_later / done_earlier come from a few ordered store queries over a call's
    candidate tasks (pour(thermos, red_mug) shares pour(thermos, green_mug)'s first object, so
    its 60 actions are candidates the answer must skip); they equal the times as logged."""
    from datetime import timedelta

    from oracle.neem.writer import NeemLogger

    store = open_store(tmp_path / "neems.sqlite")
    log = NeemLogger.create(store, onto, user="bob", neem_id="bob", commit_every=50)
    for obj in ("thermos", "green_mug", "red_mug"):
        log.perceive(obj, datetime(2024, 5, 1, 6, tzinfo=timezone.utc))
    start = datetime(2024, 5, 1, 7, tzinfo=timezone.utc)
    green: list[tuple[float, float]] = []
    for i in range(130):
        b = start + timedelta(minutes=i)
        call = "pour(thermos, green_mug)" if i in (3, 70, 71, 129) else "pour(thermos, red_mug)"
        log.action(call, b, b + timedelta(seconds=30))
        if call.endswith("green_mug)"):
            green.append((b.timestamp(), (b + timedelta(seconds=30)).timestamp()))
    log.flush()
    bridge = Bridge(store, "bob", onto)
    try:
        for minute in (0, 3.2, 3.9, 20, 69.5, 70.2, 100, 129.1, 200):
            at = start.timestamp() + minute * 60
            reasons = bridge.why_not("pour", ["thermos", "green_mug"], at)["reasons"]
            done = [b for b, e in green if b <= at <= e]
            later = [b for b, _ in green if b > at]
            earlier = [b for b, e in green if e < at]
            if done:
                expected = [{"reason": "done", "task": "pour(thermos, green_mug)", "time": min(done)}]
            elif later:
                expected = [{"reason": "done_later", "task": "pour(thermos, green_mug)", "time": min(later)}]
            else:
                expected = [{"reason": "done_earlier", "task": "pour(thermos, green_mug)", "time": max(earlier)}]
            assert [r for r in reasons if r["reason"].startswith("done")] == expected, minute
    finally:
        bridge.close()
        store.close()


def test_grouped_reply_writes_each_distinct_group_once():
    from oracle.bridge.foreign import _compact
    from oracle.store.chunks import MatchChunk

    chunk = MatchChunk(["a", "b", "c"], [(0, [1, 2]), (2, [2, 1]), (1, [1])])
    # The values in no fixed order: [b, c] and [c, b] are one group, the 4th value of the table.
    assert _compact(chunk, True) == "r(d('a','b','c'),g([2,3],[2]),[[1,4],[3,4],[2,5]])"
    assert _compact(MatchChunk([], []), True) == "r(d,g,[])"


def test_kb_group_of_shared_groups_through_the_store(tmp_path):
    store = open_store(tmp_path / "s.sqlite")
    store.create_neem("n1")
    p = "http://e.org/p"
    sets = {"s1": "xy", "s2": "yx", "s3": "x", "s4": "xyy"}
    store.insert("n1", [Triple(f"http://e.org/{s}", p, f"http://e.org/{o}") for s, os in sets.items() for o in os])
    bridge = Bridge(store, "n1")
    try:
        grouped = bridge.query(f"kb_query:kb_group(S, O, triple(S, '{p}', O), any, G)")[0]["G"]
        expected = bridge.query(f"findall(S-O, kb_call(triple(S, '{p}', O), any), P), msort(P, Q), group_pairs_by_key(Q, G)")
        assert grouped == expected[0]["G"] and len(grouped) == 4
        sizes = bridge.query(f"kb_query:kb_group(S, O, triple(S, '{p}', O), any, G),"
                             " findall(N, ( member(_-Vs, G), length(Vs, N) ), Ns)")[0]["Ns"]
        assert sizes == [2, 2, 1, 3]
    finally:
        bridge.close()


@pytest.mark.parametrize("name", ["true", "null", "false", "1.5", "[]", "ünïcødé ✓", "it's \"x\"\\"])
def test_a_request_names_values_as_data_whatever_json_would_make_of_them(tmp_path, name):
    # The store request crosses as JSON text: a name such as true or null must stay that
    # name, and a scope ending at inf (no JSON number) must still reach the store.
    store = open_store(tmp_path / "s.sqlite")
    store.create_neem("n1")
    store.insert("n1", [Triple("http://e.org/s", "http://e.org/p", name), Triple("http://e.org/s", "http://e.org/n", 2)])
    bridge = Bridge(store, "n1")
    try:
        found = bridge.query(f"kb_call(triple(S, 'http://e.org/p', {quote_atom(name)}))")
        assert [row["S"] for row in found] == ["http://e.org/s"]
        ever = bridge.query("X is inf, kb_call(triple('http://e.org/s', 'http://e.org/n', N), scope(0, X))")
        assert [row["N"] for row in ever] == [2]
        assert bridge.query("kb_call(triple('http://e.org/s', 'http://e.org/n', 2))") == [{}]
    finally:
        bridge.close()
