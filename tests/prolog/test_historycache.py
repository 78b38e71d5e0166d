"""The kept history (oracle.historycache): extended by what the logger adds, it equals the whole
history read afresh; anything else the store shows (an update, a deletion, a triple about an
earlier individual, an action in the past, other tables) makes it read the whole history. It is
kept in the store (the next process finds it), or in the user's cache where the store is
read-only; a ranking written since reads nothing through Prolog."""

from __future__ import annotations

import os
import random
from datetime import datetime, timedelta

import pytest

from oracle.bridge import Bridge
from oracle.historycache import HistoryCache
from oracle.neem import terms as T
from oracle.neem.writer import NeemLogger
from oracle.store import RDF_TYPE, open_store
from oracle.store.model import INFINITY, USER_GRAPH

CALLS = ["pick(apple)", "pour(thermos, green_mug)", "pick(banana)", "open(fridge)"]


class Counting:
    """A bridge whose whole-history reads (``full``) and reads of what was added (``after``) are counted."""

    def __init__(self, bridge: Bridge) -> None:
        self.bridge = bridge
        self.full = 0
        self.after = 0

    def __getattr__(self, name):
        return getattr(self.bridge, name)

    def history_view(self, after=None):
        if after is None:
            self.full += 1
        else:
            self.after += 1
        return self.bridge.history_view(after)


class NoProlog(Counting):
    def history_view(self, after=None):
        raise AssertionError("read again")


def _log_some(log: NeemLogger, rng: random.Random, t: datetime, n: int, durations=(2, 25), gaps=(1, 5, 30, 3600)) -> datetime:
    for _ in range(n):
        t += timedelta(seconds=rng.choice(gaps))  # idle gaps and parts of day
        for _ in range(rng.choice([0, 1, 2])):
            log.available(rng.sample(CALLS, rng.randint(1, len(CALLS))), t)
            t += timedelta(seconds=rng.choice([0, 1]))
        if rng.random() < 0.2:
            log.preference([(c, rng.random()) for c in CALLS], t)
        end = t + timedelta(seconds=rng.choice(durations))
        log.action(rng.choice(CALLS), t, end)
        t = end
    log.flush()
    return t


@pytest.fixture()
def neem(tmp_path, onto):
    store = open_store(tmp_path / "h.sqlite")
    log = NeemLogger.create(store, onto, user="r", neem_id="r")
    t = datetime(2024, 1, 1, 5)
    for obj in ("apple", "thermos", "green_mug", "banana", "fridge"):
        log.perceive(obj, t)
    rng = random.Random(3)
    t = _log_some(log, rng, t, 40)
    bridge = Bridge(store, "r", onto)
    yield store, log, bridge, rng, t
    bridge.close()


def test_grown_history_equals_the_whole_read(neem, tmp_path):
    store, log, bridge, rng, t = neem
    cache, counting = HistoryCache(tmp_path / "histories"), Counting(bridge)
    assert cache.history(counting) == bridge.history() and counting.full == 1
    for n in (1, 1, 3, 7, 0):
        t = _log_some(log, rng, t, n)
        assert cache.history(counting) == bridge.history()
    assert counting.full == 1  # every later call read only what was added
    log.available(["pick(apple)"], t + timedelta(seconds=3))  # an imagining, no action yet
    log.flush()
    assert cache.history(counting) == bridge.history() and counting.full == 1
    t = _log_some(log, rng, t + timedelta(seconds=4), 2)
    assert cache.history(counting) == bridge.history() and counting.full == 1


def test_instant_actions_and_idle_gaps_answer_the_same(neem, tmp_path):
    # An idle action after an action without duration begins when that action began: the kept
    # rows may sort after it, so the whole history is read; the answer is the same either way.
    store, log, bridge, rng, t = neem
    cache = HistoryCache(tmp_path / "histories")
    cache.history(bridge)
    for n in (1, 2, 5, 1, 3):
        t = _log_some(log, rng, t, n, durations=(0, 0, 2))
        assert cache.history(bridge) == bridge.history()


def test_nothing_added_reads_nothing(neem, tmp_path):
    store, log, bridge, rng, t = neem
    cache = HistoryCache(tmp_path / "histories")
    first = cache.history(bridge)
    assert cache.history(NoProlog(bridge)) == first


def test_the_next_process_finds_the_view_in_the_store(neem, tmp_path):
    store, log, bridge, rng, t = neem
    HistoryCache(tmp_path / "histories").view(bridge)
    assert not (tmp_path / "histories").exists()  # the store kept it
    view = HistoryCache(tmp_path / "elsewhere").view(NoProlog(bridge))
    assert view.rows == bridge.history() and view.latest == bridge.latest_situation()


def test_a_ranking_written_since_reads_nothing(neem, tmp_path):
    # rank writes its preference at the latest situation's begin, after the last action
    store, log, bridge, rng, t = neem
    cache = HistoryCache(tmp_path / "histories")
    t += timedelta(seconds=40)
    log.available(CALLS[:2], t)
    log.flush()
    cache.view(bridge)
    log.preference([(c, 0.5) for c in CALLS[:2]], t)
    log.flush()
    view = cache.view(NoProlog(bridge))
    assert view.rows == bridge.history() and view.latest == bridge.latest_situation() and view.latest["begin"] > view.rows[-1]["begin"]


def test_the_latest_situation_grows_with_the_history(neem, tmp_path):
    store, log, bridge, rng, t = neem
    cache, counting = HistoryCache(tmp_path / "histories"), Counting(bridge)
    for _ in range(3):
        t = _log_some(log, rng, t, 2)
        t += timedelta(seconds=3)
        log.available(rng.sample(CALLS, 2), t)
        log.flush()
        view = cache.view(counting)
        assert view.rows == bridge.history() and view.latest == bridge.latest_situation()
    assert counting.full == 1 and counting.after == 2


def _full_after(cache, bridge, change) -> int:
    counting = Counting(bridge)
    cache.history(counting)
    change()
    got = cache.history(counting)
    assert got == bridge.history()
    return counting.full


def _last_id(store, neem_id: str) -> int:
    return store.append_mark(neem_id).last


def test_an_update_or_a_deletion_reads_everything(neem, tmp_path):
    store, log, bridge, rng, t = neem
    cache, nid = HistoryCache(tmp_path / "histories"), bridge.neem_id
    before = store.append_mark(nid)
    assert _full_after(cache, bridge, lambda: store._rescope(nid, _last_id(store, nid), 0.0, 1e12)) == 2
    assert store.append_mark(nid).changes == before.changes + 1
    assert _full_after(cache, bridge, lambda: store._delete_triples(nid, [_last_id(store, nid)])) == 1
    assert store.append_mark(nid).changes == before.changes + 2


def test_a_triple_about_an_earlier_individual_reads_everything(neem, tmp_path, onto):
    store, log, bridge, rng, t = neem
    cache = HistoryCache(tmp_path / "histories")
    nid = bridge.neem_id
    task = next(doc["o"] for doc in store.find(nid, p=T.EXECUTES))  # an earlier action's task
    extra = (task, RDF_TYPE, onto.task_iri("pick"), USER_GRAPH, 0.0, INFINITY)
    assert _full_after(cache, bridge, lambda: store.insert(nid, [extra])) == 2
    assert not store.appended(nid, _last_id(store, nid) - 1).fresh


def test_an_action_logged_in_the_past_reads_everything(neem, tmp_path, onto):
    store, log, bridge, rng, t = neem
    cache = HistoryCache(tmp_path / "histories")
    first = datetime(2024, 1, 1, 5, 0, 1)  # before every action
    late = NeemLogger(store, onto, bridge.neem_id)
    late._clock_resumed, late._last_end, late._last_begin = True, None, None  # a recorded action, logged late
    assert _full_after(cache, bridge, lambda: (late.action("pick(apple)", first, first), late.flush())) == 2
    assert bridge.history()[0]["call"] == "pick(apple)" and bridge.history()[0]["begin"] == first.timestamp()


def test_a_replaced_neem_reads_everything(neem, tmp_path, onto):
    store, log, bridge, rng, t = neem
    cache = HistoryCache(tmp_path / "histories")
    counting = Counting(bridge)
    cache.history(counting)
    token = store.append_mark(bridge.neem_id).token
    bridge.close()
    again = NeemLogger.create(store, onto, user="r", neem_id="r", replace=True)
    _log_some(again, random.Random(9), datetime(2025, 1, 1), 5)
    again.close()
    fresh = Bridge(store, "r", onto)
    assert store.append_mark(fresh.neem_id).token != token
    counting = Counting(fresh)
    assert cache.history(counting) == fresh.history() and counting.full == 1
    fresh.close()


def test_a_damaged_entry_in_the_store_is_not_used(neem, tmp_path):
    import json

    from oracle.historycache import KIND

    store, log, bridge, rng, t = neem
    cache, nid = HistoryCache(tmp_path / "histories"), bridge.neem_id
    cache.history(bridge)
    kept = store.read_kept(nid, KIND)
    store.write_kept(nid, KIND, b"{not json")
    counting = Counting(bridge)
    assert cache.history(counting) == bridge.history() and counting.full == 1
    data = json.loads(kept)
    data["history"]["rows"][0] = "soon"  # valid JSON, not a history
    store.write_kept(nid, KIND, json.dumps(data).encode())
    counting = Counting(bridge)
    assert cache.history(counting) == bridge.history() and counting.full == 1
    data = json.loads(kept)
    data["latest"] = {"begin": "soon", "available": [], "part": "none"}
    store.write_kept(nid, KIND, json.dumps(data).encode())
    counting = Counting(bridge)
    assert cache.history(counting) == bridge.history() and counting.full == 1


def test_a_damaged_or_foreign_entry_is_not_used(neem, tmp_path):
    store, log, bridge, rng, t = neem
    bridge.close()
    reader = open_store(tmp_path / "h.sqlite", read_only=True)  # keeps nothing: the user's cache does
    bridge = Bridge(reader, "r", log.onto)
    cache = HistoryCache(tmp_path / "histories")
    cache.history(bridge)
    (entry,) = (tmp_path / "histories").glob("*.json")
    entry.write_bytes(b"{not json")
    counting = Counting(bridge)
    assert cache.history(counting) == bridge.history() and counting.full == 1
    import json

    data = json.loads(entry.read_bytes())
    data["history"]["rows"][0] = "soon"  # valid JSON, not a history
    entry.write_text(json.dumps(data))
    counting = Counting(bridge)
    assert cache.history(counting) == bridge.history() and counting.full == 1
    os.chmod(entry, 0o666)
    counting = Counting(bridge)
    assert cache.history(counting) == bridge.history() and counting.full == 1
    assert entry.stat().st_mode & 0o077 == 0  # replaced, private again


def test_an_unwritable_cache_still_answers(neem, tmp_path):
    store, log, bridge, rng, t = neem
    blocked = tmp_path / "file"
    blocked.write_text("")
    assert HistoryCache(blocked / "histories").history(bridge) == bridge.history()


def test_a_store_that_cannot_tell_reads_everything(neem, tmp_path, monkeypatch):
    store, log, bridge, rng, t = neem
    monkeypatch.setattr(type(store), "append_mark", lambda self, neem_id: None)
    counting = Counting(bridge)
    cache = HistoryCache(tmp_path / "histories")
    cache.history(counting)
    cache.history(counting)
    assert counting.full == 2 and not (tmp_path / "histories").exists()


def test_a_temporary_neem_is_never_kept(tmp_path, onto):
    # A session NEEM not yet persisted is wiped when the next session starts (thesis 3.5):
    # nothing read from it may stay in the user's cache.
    store = open_store(tmp_path / "t.sqlite")
    log = NeemLogger.create(store, onto, user="s", neem_id="s", temporary=True)
    _log_some(log, random.Random(1), datetime(2024, 1, 1, 5), 5)
    bridge = Bridge(store, "s", onto)
    cache = HistoryCache(tmp_path / "histories")
    assert cache.history(bridge) == bridge.history()
    assert not (tmp_path / "histories").exists() and store.read_kept(bridge.neem_id, "history") is None
    bridge.close()


def test_many_added_triples_are_read_whole(neem, tmp_path, monkeypatch):
    import oracle.historycache as kept_module

    store, log, bridge, rng, t = neem
    cache, counting = HistoryCache(tmp_path / "histories"), Counting(bridge)
    cache.history(counting)
    monkeypatch.setattr(kept_module, "MAX_APPENDED", 10)
    t = _log_some(log, rng, t, 3)  # ~40 triples an action
    assert cache.history(counting) == bridge.history() and counting.full == 2


def test_a_preference_for_an_earlier_decision_keeps_the_history(neem, tmp_path):
    # The robot logs an action with what was available (the imagining begins with it), a rank
    # of that latest situation writes its preference at the same begin; the next actions still
    # extend the kept history (a preference is neither an action nor an imagining).
    store, log, bridge, rng, t = neem
    cache, counting = HistoryCache(tmp_path / "histories"), Counting(bridge)
    for _ in range(3):
        t += timedelta(seconds=7)
        log.action("pick(apple)", t, t + timedelta(seconds=2), available=CALLS)
        log.flush()
        assert cache.history(counting) == bridge.history()
        log.preference([(c, 0.5) for c in CALLS], t)  # at the last kept row's begin
        log.flush()
        t += timedelta(seconds=2)
    assert counting.full == 1
    assert cache.history(counting) == bridge.history() and counting.full == 1


def test_an_imagining_at_the_last_begin_reads_everything(neem, tmp_path):
    # An imagining added at the last kept action's begin is one the kept rows could have used.
    store, log, bridge, rng, t = neem
    cache, counting = HistoryCache(tmp_path / "histories"), Counting(bridge)
    cache.history(counting)
    last = bridge.history()[-1]["begin"]
    late = NeemLogger(store, log.onto, bridge.neem_id)
    late._clock_resumed, late._last_end, late._last_begin = True, None, None  # a recorded imagining, logged late
    late.available(["pick(banana)"], datetime.fromtimestamp(last))
    late.flush()
    assert cache.history(counting) == bridge.history() and counting.full == 2


def test_a_damaged_later_entry_gives_way_to_the_earlier_one(neem, tmp_path):
    # entries are judged by their mark first; the chosen one, damaged past its mark, gives way
    import json

    from oracle.historycache import _entry_key, _file_name

    store, log, bridge, rng, t = neem
    cache = HistoryCache(tmp_path / "histories")
    cache.history(bridge)  # kept in the store at this mark
    _log_some(log, rng, t, 3)
    latest = bridge.history_view()
    mark = store.append_mark(bridge.neem_id)
    data = {"format": "neem-oracle history 3", "key": _entry_key(bridge), "mark": [mark.token, mark.changes, mark.last],
            "history": {"calls": [], "sets": [], "rows": ["soon"]}, "latest": None}
    (tmp_path / "histories").mkdir(mode=0o700)
    path = tmp_path / "histories" / f"{_file_name(_entry_key(bridge), store.location)}.json"
    path.write_text(json.dumps(data, separators=(",", ":")))
    os.chmod(path, 0o600)
    counting = Counting(bridge)
    view = cache.view(counting)
    assert (counting.full, counting.after) == (0, 1)  # the store's entry, extended
    assert view.rows == latest.rows and view.latest == latest.latest
