"""What a session keeps per history (oracle.service.warm) answers as the uncached path does: the
routine in progress (oracle.past.routines.in_progress over the routines mined from the actions
done, named by the stored workflows) and the usual modes (ranked_modes with the logit fitted
afresh), step after step, across idle gaps, and after actions logged by someone else's mode."""

from __future__ import annotations

import numpy as np

from oracle.algorithm.params import Hyperparameters
from oracle.neem.writer import NeemLogger
from oracle.past.modelogit import fit_modes, ranked_modes
from oracle.past.routines import begun_by, done_from_steps, in_progress, mine_routines
from oracle.past.workflows import keep_user_names
from oracle.service.engine import Engine
from oracle.service.robot import persona_rows
from oracle.store import open_store
from oracle.timeline import Instant


def _uncached(session, at, stored):
    ranker = session.ranker
    done = begun_by(done_from_steps(ranker.steps, ranker.begins, ranker.last_end), at)
    routines, _ = keep_user_names(mine_routines(done), stored)
    return in_progress(routines, done, at) if done else None


def test_kept_routines_and_modes_answer_as_afresh(tmp_path, onto):
    _, rows = persona_rows(0, 3, 12)
    store = open_store(tmp_path / "s.sqlite")
    logger = NeemLogger.create(store, onto, user="ann", neem_id="ann", commit_every=500)
    for row in rows[:300]:
        logger.action(row.action, row.time, row.end, available=row.available)
    logger.flush()
    engine = Engine(store, onto, Hyperparameters())
    session = engine.session("ann")
    stored = [{"name": "breakfast", "steps": [str(r.action) for r in rows[:6]], "by_user": True}]
    found = 0
    for index, row in enumerate(rows[300:360]):
        performer = ("robot", "user", "together")[index % 3]
        now = Instant.of(row.time).seconds
        for at in (now, now + 4 * 3600):  # now, and after an idle gap
            want = _uncached(session, at, stored)
            _, got = session.warm.in_progress(session.ranker, at, stored)
            assert got == want
            found += want is not None
        kept, afresh = session.warm.modes(session.ranker), fit_modes(session.ranker.modes)
        assert kept.rows == afresh.rows and np.array_equal(kept.weights, afresh.weights)
        calls = [str(c) for c in row.available or (row.action,)]
        for part in ("Morning", "Evening"):
            assert ranked_modes(session.ranker.modes, calls, calls[:3], part, session.warm.modes(session.ranker)) \
                == ranked_modes(session.ranker.modes, calls, calls[:3], part)
        session.log(str(row.action), row.time.isoformat(), row.end.isoformat() if row.end else None, performer)
        if index % 2:
            session.warm.warm(session.ranker, session.ranker.last_end)
    assert found > 10  # routines were in progress, not only None compared with None
    store.close()


def _ann(tmp_path, onto, n: int):
    """A store holding ann's NEEM of a persona's first ``n`` actions."""
    store = open_store(tmp_path / "s.sqlite")
    logger = NeemLogger.create(store, onto, user="ann", neem_id="ann")
    _, rows = persona_rows(0, 1, 12)
    for row in rows[:n]:
        logger.action(row.action, row.time, row.end, available=row.available)
    logger.flush()
    return store


def test_warm_up_loads_the_answers_prolog_and_words_before_the_first_question_and_reads_no_neem(tmp_path, onto):
    from oracle.bridge.engine import STATE

    empty = Engine(open_store(tmp_path / "empty.sqlite"), onto, Hyperparameters())
    empty.warm_up()  # a store without NEEMs: the words only
    assert empty.past._lexicon is not None and empty._bridge is None
    store = _ann(tmp_path, onto, 5)
    engine = Engine(store, onto, Hyperparameters())
    engine.warm_up()
    assert STATE["loaded"] and engine._bridge is not None
    assert engine._bridge.ask("current_predicate(odb_past:past_answer_json/1)", [])
    assert not engine.past._entries  # nothing of the NEEM read or kept


def test_boot_warms_the_engine_up_and_freezes_what_the_boot_made(tmp_path, onto):
    import gc

    import re

    from oracle.past.forms import FORMS
    from oracle.service import boot, build_context
    from oracle.service.app import create_app

    ctx = build_context(str(tmp_path / "b.sqlite"), onto, Hyperparameters())
    try:
        app = create_app(ctx)
        assert app.middleware_stack is None  # Starlette builds it on its first request
        re.purge()
        boot(ctx, app)
        assert ctx.thread.call(lambda: ctx.engine.past._lexicon) is not None
        assert gc.get_freeze_count() > 0
        assert app.middleware_stack is not None  # the first request went through the app at boot
        pattern = FORMS[0].patterns[0][1]
        assert any(key[1] == pattern for key in re._cache)  # type: ignore[attr-defined]  # the forms compiled
    finally:
        gc.unfreeze()  # the test process goes on collecting as before
        ctx.thread.close()


def test_the_stored_workflows_are_read_once_then_after_an_action_at_most_every_stored_s(monkeypatch):
    from oracle.service import warm as warm_module
    from oracle.service.warm import Warm

    reads: list[int] = []

    def read() -> list[dict]:
        reads.append(1)
        return [{"name": f"read {len(reads)}", "steps": [], "by_user": True}]

    class _Ranker:  # what warm() reads of a ranker, with no action counted
        steps: list = []
        begins: list = []
        last_end = None
        clocked = False

        class modes:
            counts: dict = {}

    kept = Warm()
    monkeypatch.setattr(warm_module, "fit_modes", lambda counts: object())
    assert kept.stored(read)[0]["name"] == "read 1"
    assert kept.stored(read)[0]["name"] == "read 1" and len(reads) == 1  # a situation: no read
    kept.warm(_Ranker(), None, read)  # an action within STORED_S: no read either
    assert len(reads) == 1
    monkeypatch.setattr(warm_module, "STORED_S", 0.0)
    kept.warm(_Ranker(), None, read)
    assert kept.stored(read)[0]["name"] == "read 2"


def test_the_kept_clustering_mines_the_routines_of_mining_all_at_once():
    """Warm keeps the clustering of every episode but the last and grows it: after each action
    of three simulated weeks, the routines are those of mining the actions afresh."""
    from oracle.past.routines import Done, episodes_of
    from oracle.service.warm import Warm

    _, rows = persona_rows(1, 5, 21)
    done = [Done(row.time.timestamp(), (row.end or row.time).timestamp(), str(row.action)) for row in rows]
    kept = Warm()
    found = 0
    for count in range(1, len(done), 3):
        mined = kept._mine(episodes_of(done[:count]))
        assert mined == mine_routines(done[:count])
        found += bool(mined)
    assert found > 10  # routines were found, not only empty lists compared


def test_the_kept_episodes_cut_as_cutting_all_at_once():
    """Warm cuts only the actions from the last episode on again while the earlier ones are the
    same objects: the episodes of each action list are those of cutting it afresh, when the
    last action's end changes (a new object) and when the list is made anew."""
    from dataclasses import replace

    from oracle.past.routines import Done, episodes_of
    from oracle.service.warm import Warm

    _, rows = persona_rows(2, 5, 14)
    made = [Done(row.time.timestamp(), (row.end or row.time).timestamp(), str(row.action)) for row in rows]
    kept, done = Warm(), []
    for count, action in enumerate(made):
        # as Warm.done makes it: the earlier actions the same objects, the last one made again
        done = done[:-1] + [replace(done[-1])] + [action] if done else [action]
        if count % 50 == 49:
            done = list(map(lambda d: replace(d), done))  # made anew: nothing kept applies
        assert kept._episodes(done) == episodes_of(done)
    assert kept._cut is not None and len(episodes_of(done)) > 20


def test_a_session_opened_is_frozen_out_of_the_collectors_view(tmp_path, onto):
    import gc

    store = _ann(tmp_path, onto, 20)
    engine = Engine(store, onto, Hyperparameters())
    gc.unfreeze()
    try:
        session = engine.session("ann")
        assert gc.get_freeze_count() > 0
        assert not any(obj is session for obj in gc.get_objects())  # frozen: not scanned by a collection
    finally:
        gc.unfreeze()
        store.close()
