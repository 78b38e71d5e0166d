"""The rule "what followed X" has two homes held equal: prolog/odb/past.pl's usual_after/3 (the
Prolog answer) and oracle.past.routines.follows (the service's, on the kept history)."""

from __future__ import annotations

from datetime import datetime

from oracle.past.evidence import request
from oracle.past.routines import done_from_history, follows


def test_follows_equals_usual_after_on_the_hand_checked_neem(bridge):
    _same_for_every_call(bridge)


def test_follows_equals_usual_after_on_a_simulated_week(tmp_path, onto):
    from oracle.bridge import Bridge
    from oracle.neem.writer import NeemLogger
    from oracle.store import open_store
    from oracle.world.generate import simulate
    from oracle.world.personas import make_persona
    from oracle.world.worldfile import load_world

    rows, _ = simulate(make_persona(5, 2), load_world(), 3, 5)
    store = open_store(tmp_path / "w.sqlite")
    log = NeemLogger.create(store, onto, user="w", neem_id="week", commit_every=500)
    for row in rows:
        assert isinstance(row.time, datetime)
        log.action(row.action, row.time, row.end)
    log.close()
    bridge = Bridge(store, "week", onto)
    try:
        _same_for_every_call(bridge)
    finally:
        bridge.close()
        store.close()


def _same_for_every_call(bridge) -> None:
    from oracle.chains import parse_call

    done = done_from_history(bridge.history())
    calls = sorted({d.call for d in done})
    assert len(calls) > 3
    for call in calls:
        parsed = parse_call(call)
        prolog = request(bridge, ["after", parsed.task, list(parsed.args)])
        n, counts = follows(done, call)
        assert (prolog["occurrences"], [(c["task"], c["count"]) for c in prolog["next"]]) == (n, counts), call
