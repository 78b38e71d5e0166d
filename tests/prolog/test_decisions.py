"""The latest decision of a kind (odb_decisions:latest_decision/4) on a NEEM written by the
logger: the latest begin wins, ties go to the greatest in the standard order of terms, a time
bound is kept, and a NEEM holding fewer decisions than one batch of the query answers alike."""

from __future__ import annotations

from datetime import datetime, timedelta, timezone

import pytest

from oracle.bridge import Bridge
from oracle.neem.writer import NeemLogger
from oracle.store import open_store

CALLS = ["pick(apple)", "pour(thermos, green_mug)"]
T0 = datetime(2024, 5, 1, 8, tzinfo=timezone.utc)


def latest(bridge: Bridge, kind: str, test: str = "any") -> tuple[str, float] | None:
    rows = bridge.query(f"odb_decisions:latest_decision({kind}, {test}, M, B)")
    return (rows[0]["M"], rows[0]["B"]) if rows else None


@pytest.fixture()
def neem(tmp_path, onto):
    store = open_store(tmp_path / "d.sqlite")
    log = NeemLogger.create(store, onto, user="r", neem_id="r")
    for obj in ("apple", "thermos", "green_mug"):
        log.perceive(obj, T0)
    t = T0
    for i in range(30):  # situations at every step, an action after each
        t += timedelta(minutes=1)
        log.available(CALLS, t)
        log.action(CALLS[i % 2], t + timedelta(seconds=1), t + timedelta(seconds=20))
    log.flush()
    bridge = Bridge(store, "r", onto)
    yield store, log, bridge, t
    bridge.close()
    store.close()


def test_no_preference_then_one_far_back_then_ties_at_the_latest_begin(neem):
    store, log, bridge, t = neem
    assert latest(bridge, "preference") is None
    situation = latest(bridge, "situation")
    assert situation is not None and situation[1] == t.timestamp()
    early = T0 + timedelta(minutes=3)
    log.preference([(CALLS[0], 0.1)], early)          # one preference, 27 situations later on
    log.flush()
    only = latest(bridge, "preference")
    assert only is not None and only[1] == early.timestamp()
    written = [log.preference([(c, 0.5)], t) for c in CALLS * 5]  # ten at one begin: more than a batch
    log.flush()
    tied = bridge.query(f"findall(M, odb_decisions:decision(preference, M, {t.timestamp()}), Ms)")[0]["Ms"]
    assert len(tied) == len(written) == 10
    assert latest(bridge, "preference") == (max(tied), t.timestamp())
    # a time bound before the ties: the one far back
    assert latest(bridge, "preference", f"=<({(t - timedelta(seconds=1)).timestamp()})") == only
    assert latest(bridge, "preference", f"=<({early.timestamp() - 1})") is None


def test_the_current_task_is_the_latest_action_also_among_more_ties_than_a_batch(neem):
    """something_else/2 without a task asks for the latest action: fetched in ordered chunks,
    it is the one the whole sorted list of executions gives (latest begin, greatest task)."""
    store, log, bridge, t = neem
    end = t + timedelta(minutes=5)
    for i in range(20):  # twenty instant actions at one begin: more than the first chunk
        log.action(CALLS[i % 2], end, end)
    log.flush()
    reference = bridge.query(
        "odb_names:odb_iri('IdleTask', Idle),"
        "findall(B-T, kb_call((executes_task(A, T), has_time_interval(A, I), has_interval_begin(I, B)), any), P),"
        "sort(0, @>=, P, S), member(B0-T0, S), \\+ kb_call(instance_of(T0, Idle), any),"
        "odb_calls:task_call(T0, C), !, term_string(C, Text)")[0]
    assert reference["B0"] == end.timestamp()
    latest = bridge.query("answers:latest_action(C, B), term_string(C, Text)")[0]
    assert (latest["Text"], latest["B"]) == (reference["Text"], reference["B0"])


def test_with_many_decisions_the_ordered_queries_answer_as_every_decision_does(neem):
    """Past 64 decisions of a kind latest_decision/4 switches from reading them all to the
    ordered scans; both give the latest passing the test, ties to the greatest."""
    store, log, bridge, t = neem
    for i in range(40):  # 70 situations in all, then five more at the latest begin
        t += timedelta(minutes=1)
        log.available(CALLS, t)
        log.action(CALLS[i % 2], t + timedelta(seconds=1), t + timedelta(seconds=20))
    t += timedelta(minutes=1)
    for _ in range(5):
        log.available(CALLS, t)
    log.flush()
    everything = bridge.query("findall(B-M, odb_decisions:decision(situation, M, B), L), length(L, N)")[0]["N"]
    assert everything == 75
    rows = bridge.query("findall(M, odb_decisions:decision(situation, M, _), Ms),"
                        "findall(B, odb_decisions:decision(situation, _, B), Bs)")[0]
    pairs = list(zip((float(b) for b in rows["Bs"]), rows["Ms"]))
    for bound in (None, (t - timedelta(minutes=3)).timestamp(), (t - timedelta(seconds=30)).timestamp()):
        passing = [(b, m) for b, m in pairs if bound is None or b <= bound]
        top = max(b for b, _ in passing)
        expected = (max(m for b, m in passing if b == top), top)
        assert latest(bridge, "situation", "any" if bound is None else f"=<({bound})") == expected
    assert latest(bridge, "situation", f"=<({T0.timestamp()})") is None
