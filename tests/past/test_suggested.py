"""``why did you suggest X``: the preferences are read latest first a page at a time
(odb_decisions:latest_first/4), in the order of every preference read and sorted, on a NEEM
ranked more often than the few read whole (a ranking per action, as the service writes)."""

from __future__ import annotations

import pytest

from oracle.timeline import seconds_of
from tests.past.conftest import t

CALLS = ("open(fridge)", "pick(apple)", "pick(green_mug)", "pick(milk_carton)")


@pytest.fixture()
def ranked_bridge(tmp_path, onto):
    """90 rankings a minute apart, two more at the time of the 41st and of the 75th (where the
    first page of the latest ends); pick(milk_carton) ranked by the 11th alone."""
    from oracle.bridge import Bridge
    from oracle.neem.writer import NeemLogger
    from oracle.past.evidence import ensure_loaded
    from oracle.store import open_store

    store = open_store(tmp_path / "ranked.sqlite")
    log = NeemLogger.create(store, onto, user="sam", neem_id="ranked")
    for n in range(90):
        at = seconds_of(t(0, 7)) + 60 * n
        offered = list(CALLS[:3]) if n != 10 else list(CALLS)
        for repeat in range(2 if n in (40, 74) else 1):
            log.available(offered, at)
            log.preference([(c, 0.1 * ((i + n + repeat) % len(offered))) for i, c in enumerate(offered)], at)
        log.action(offered[n % 3], at + 5, at + 15)
    log.close()
    bridge = Bridge(store, "ranked", onto)
    ensure_loaded(bridge)
    yield bridge
    bridge.close()
    store.close()


def _same(bridge, before: str) -> bool:
    query = (f"findall(B-M, odb_decisions:latest_first(preference, {before}, B, M), Paged), "
             f"findall(B-M, ( odb_decisions:decision(preference, M, B), ( {before} == none -> true ; B =< {before} ) ), Pairs), "
             "sort(0, @>=, Pairs, Sorted), length(Paged, N), ( Paged == Sorted -> R = yes ; R = no )")
    row = bridge.query(query)[0]
    return row["R"] == "yes" and row["N"] > 0


def test_preferences_are_read_latest_first_as_all_of_them_sorted(ranked_bridge):
    first = seconds_of(t(0, 7))
    for before in ("none", repr(first + 60 * 89), repr(first + 60 * 40), repr(first + 60 * 40 + 0.5), repr(first + 30)):
        assert _same(ranked_bridge, before), before


def test_why_did_you_suggest_reads_back_past_the_latest(ranked_bridge, onto):
    from oracle.past.ask import ask

    answer = ask(ranked_bridge, onto, "why did you suggest pick(milk_carton)?")
    assert answer.evidence["time"] == pytest.approx(seconds_of(t(0, 7)) + 600)
    latest = ask(ranked_bridge, onto, "why did you suggest open(fridge)?").evidence
    assert latest["time"] == pytest.approx(seconds_of(t(0, 7)) + 60 * 89)
    for call in CALLS:  # as every preference read, sorted, and tried latest first
        reference = ("findall(B-M, odb_decisions:decision(preference, M, B), Pairs), sort(0, @>=, Pairs, Latest), "
                     f"once(( member(T-M, Latest), odb_decisions:imagined_preference(M, Ranked), "
                     f"memberchk(ranked({call}, Rank, Score), Ranked) )), Ranked = [Top|_], "
                     "S = suggested(T, Rank, Score, Top)")
        paged = ranked_bridge.query(f"odb_past:suggestion({call}, none, S)")
        assert paged[0]["S"] == ranked_bridge.query(reference)[0]["S"]
