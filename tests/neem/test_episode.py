"""KnowRob's episode structure in the NEEMs we write (neem-interface's ``mem_episode_start``,
``add_subaction_with_task``, ``mem_event_set_succeeded``), and KnowRob's extent rule on them."""

from __future__ import annotations

import shutil
from datetime import datetime

import pytest

from oracle.errors import LoggingError
from oracle.namespaces import DUL_IRI, SOMA_IRI
from oracle.neem.query import count_actions
from oracle.neem.writer import NeemLogger
from oracle.store import RDF_TYPE, open_store

EPISODE, INCLUDES, CONSTITUENT = SOMA_IRI + "Episode", DUL_IRI + "includesAction", DUL_IRI + "hasConstituent"


@pytest.fixture(scope="module")
def onto():
    from oracle.ontology import build_ontology

    return build_ontology()


def two_days(store, onto) -> NeemLogger:
    log = NeemLogger.create(store, onto, user="u", neem_id="u")
    log.action("pick(apple)", datetime(2024, 5, 1, 8, 0), state="succeeded")  # instantaneous
    log.action("pour(thermos, green_mug)", datetime(2024, 5, 1, 8, 1), datetime(2024, 5, 1, 8, 3), state="failed")
    log.action("pick(apple)", datetime(2024, 5, 2, 9, 0), datetime(2024, 5, 2, 9, 1))
    log.close()
    return log


def test_one_episode_per_day_with_constituents_states_and_named_tasks(tmp_path, onto) -> None:
    store = open_store(tmp_path / "s.sqlite")
    n = two_days(store, onto).neem_id
    episodes = [d["s"] for d in store.find(n, p=RDF_TYPE, o=EPISODE, exact=True)]
    assert len(episodes) == 2 and all(e.startswith(EPISODE + "_") for e in episodes)
    tops = [next(store.find(n, s=e, p=INCLUDES))["o"] for e in episodes]
    constituents = sorted(len(list(store.find(n, s=t, p=CONSTITUENT))) for t in tops)
    # day 1: pick, the idle minute after it, pour; day 2: the idle night before it, pick
    assert constituents == [2, 3]
    # each top-level action's interval: the first begin to the latest end of its day
    spans = sorted((_f(b["o"]), _f(e["o"])) for t in tops
                   for i in [next(store.find(n, s=t, p=DUL_IRI + "hasTimeInterval"))["o"]]
                   for b in store.find(n, s=i, p=SOMA_IRI + "hasIntervalBegin")
                   for e in store.find(n, s=i, p=SOMA_IRI + "hasIntervalEnd"))  # fmt: skip
    assert spans == [(datetime(2024, 5, 1, 8, 0).timestamp() - _tz(), datetime(2024, 5, 1, 8, 3).timestamp() - _tz()),
                     (datetime(2024, 5, 1, 8, 3).timestamp() - _tz(), datetime(2024, 5, 2, 9, 1).timestamp() - _tz())]
    states = sorted(d["o"] for d in store.find(n, p=SOMA_IRI + "hasExecutionState"))
    # the third action gave no state: logged as done, it succeeded
    assert states == [SOMA_IRI + "ExecutionState_Failed"] + [SOMA_IRI + "ExecutionState_Succeeded"] * 2
    # tasks named <TaskClass>_<id>, as KnowRob's new_iri names individuals, the class's local
    # name in CamelCase (one `_` in all, for openEASE's timeline rule)
    executed = [d["o"] for d in store.find(n, p=DUL_IRI + "executesTask")]
    for task in executed:
        classes = [d["o"] for d in store.find(n, s=task, p=RDF_TYPE, exact=True)]
        assert task.count("_") == 1, task
        assert any(task.split("_")[0].lower() == c.replace("_", "").lower() for c in classes), (task, classes)
    assert count_actions(store, n)[0] == 5  # 3 + 2 idle; the top-level actions are no executed actions
    # KnowRob's extent rule: no fact of the NEEM has since >= until
    scopes = [d["scope"]["time"] for d in store.find(n) if "scope" in d]
    assert len(scopes) > 50
    empty = [t for t in scopes if not _f(t["since"]) < _f(t["until"])]
    assert empty == []
    store.close()


def _f(value) -> float:
    return float(value.to_decimal()) if hasattr(value, "to_decimal") else float(value)


def _tz() -> float:
    """Naive datetimes are read as UTC (docs/time.md); ``timestamp()`` reads them as local."""
    return datetime(2024, 5, 1).timestamp() - datetime(2024, 5, 1).replace(tzinfo=__import__("datetime").timezone.utc).timestamp()


def test_bad_state_or_session_is_refused_and_writes_nothing(tmp_path, onto) -> None:
    store = open_store(tmp_path / "s.sqlite")
    log = NeemLogger.create(store, onto, user="u", neem_id="u")
    before = sum(1 for _ in store.find(log.neem_id))
    with pytest.raises(LoggingError, match="state must be one of"):
        log.action("pick(apple)", datetime(2024, 5, 1, 8, 0), state="done")
    with pytest.raises(LoggingError, match="session must be"):
        log.action("pick(apple)", datetime(2024, 5, 1, 8, 0), session=" ")
    assert sum(1 for _ in store.find(log.neem_id)) == before
    store.close()


@pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed")
def test_knowrob_sees_the_episode_roles_and_states(tmp_path, onto) -> None:
    from oracle.bridge import Bridge

    store = open_store(tmp_path / "s.sqlite")
    bridge = Bridge(store, two_days(store, onto).neem_id, onto)
    try:
        assert len(bridge.query("findall(E, kb_call(is_episode(E), any), Es), sort(Es, S), length(S, N)")[0]["S"]) == 2
        subs = bridge.query("findall(A, kb_call((is_episode(E), is_setting_for(E, Top), has_subevent(Top, A)), any), L),"
                            " length(L, N)")  # fmt: skip
        assert subs[0]["N"] == 5
        # the instantaneous action's role is returned by `has_role during A`, as KnowRob returns it
        rows = bridge.query("findall(O, ( kb_call(action_succeeded(A), any), kb_call(has_role(O, _R) during A) ), Os)")
        # both picks succeeded (the second logged with no state: done): during each, the apple's
        # role (the first's scoped to the instant's extent) and the robot's agent roles (always)
        assert sorted(o.rsplit("#", 1)[-1] for o in rows[0]["Os"]) == ["Agent_robot"] * 4 + ["Object_apple"] * 2
        assert bridge.query("findall(A, kb_call(action_failed(A), any), L), length(L, N)")[0]["N"] == 1
    finally:
        bridge.close()
        store.close()
