"""What the answers keep of a NEEM between answers (oracle.past.kept): every answer read through
what was kept equals the answer read afresh, before and after the NEEM grows (an action, a
ranking, a saved workflow), and the routines are mined again only when the actions changed."""

from __future__ import annotations

import shutil
from dataclasses import replace

import pytest

from oracle.past.ask import ask
from oracle.past.kept import KeptPast
from oracle.past.mine import neem_preparation, neem_routines
from oracle.past.summary import state_summary
from oracle.timeline import seconds_of
from tests.past.conftest import t

#: One question of every form, and a suggestion the NEEM has.
QUESTIONS = ("when did I last open the fridge?", "how often did I open(fridge) this week?",
             "what do I usually do after open(fridge)?", "what did you do today?", "where is the green mug?",
             "why did you suggest open(fridge)?", "why did you suggest pick(green_mug)?",
             "who usually does open(fridge)?", "Wann habe ich zuletzt pick(apple) gemacht?")


@pytest.fixture()
def grown(small_store, onto, tmp_path):
    """The hand-checked NEEM in a copy that the test may log more actions into."""
    from oracle.bridge import Bridge
    from oracle.neem.writer import NeemLogger
    from oracle.store import open_store

    copy = tmp_path / "small.sqlite"
    shutil.copy(small_store, copy)
    store = open_store(copy)
    bridge = Bridge(store, "small", onto)
    logger = NeemLogger(store, onto, bridge.neem_id)
    yield bridge, logger
    bridge.close()
    store.close()


def answers(bridge, onto, kept):
    asked = [ask(bridge, onto, q, kept=kept).to_json() for q in QUESTIONS]
    return asked + [state_summary(bridge, kept=kept), neem_routines(bridge, kept=kept).to_json(),
                    neem_preparation(bridge, "Morning", kept=kept)]


def test_kept_answers_equal_fresh_ones_as_the_neem_grows(grown, onto):
    bridge, logger = grown
    kept = KeptPast()
    before = answers(bridge, onto, kept)
    assert before == answers(bridge, onto, None) and answers(bridge, onto, kept) == before

    logger.action("open(fridge)", t(1, 8, 2), t(1, 8, 2, 10))
    logger.action("pick(apple)", t(1, 8, 2, 15), t(1, 8, 2, 25))
    logger.flush()
    after = answers(bridge, onto, kept)
    assert after == answers(bridge, onto, None)
    after_fridge = after[QUESTIONS.index("what do I usually do after open(fridge)?")]["evidence"]
    assert after_fridge["occurrences"] == 4 and {"task": "pick(apple)", "count": 2} in after_fridge["next"]
    assert after[len(QUESTIONS)]["latest"]["task"] == "pick(apple)"

    logger.available(["pick(apple)", "open(fridge)"], t(1, 8, 3))
    logger.preference([("open(fridge)", 0.2), ("pick(apple)", 0.4)], t(1, 8, 3))
    logger.flush()  # a ranking only: the actions are the same, the suggestion is new
    ranked = answers(bridge, onto, kept)
    assert ranked == answers(bridge, onto, None)
    assert ranked[QUESTIONS.index("why did you suggest open(fridge)?")]["evidence"]["rank"] == 1


def test_the_routines_are_mined_again_only_when_the_actions_changed(routine_store, onto, monkeypatch):
    from oracle.bridge import Bridge
    from oracle.neem.writer import NeemLogger
    from oracle.past import kept as kept_module
    from oracle.past.workflows import save_routines
    from oracle.store import open_store
    from tests.past.test_routines import BREAKFAST, day

    minings = []
    mine = kept_module.mine_routines
    monkeypatch.setattr(kept_module, "mine_routines", lambda *a: minings.append(1) or mine(*a))
    store = open_store(routine_store)
    bridge = Bridge(store, "weekly", onto)
    kept = KeptPast()
    try:
        first = neem_routines(bridge, kept=kept)
        assert first.current is not None and first.current.done == 3
        assert neem_routines(bridge, kept=kept) == first == neem_routines(bridge) and len(minings) == 2

        logger = NeemLogger(store, onto, bridge.neem_id)
        step = day(4, 7, BREAKFAST)[3]
        logger.available(["pick(apple)"], step.begin - 3)
        logger.preference([("pick(apple)", 0.5)], step.begin - 3)
        logger.flush()  # a ranking: the actions, so the routines, are the same
        assert neem_routines(bridge, kept=kept) == first and len(minings) == 2

        logger.action(step.call, step.begin, step.end)
        logger.flush()
        grown = neem_routines(bridge, kept=kept)
        assert grown == neem_routines(bridge) and grown.current is not None and grown.current.done == 4
        assert len(minings) == 4  # the kept one and the fresh one
        assert neem_routines(bridge, first.now, kept=kept) == first == neem_routines(bridge, first.now)
        assert len(minings) == 5  # as of before the action: the kept mining (and the fresh one)

        key = grown.routines[0].key
        named = tuple(replace(r, name="My breakfast") if r.key == key else r for r in grown.routines)
        save_routines(store, onto, "weekly", named, (key,))
        renamed = neem_routines(bridge, kept=kept)
        assert renamed == neem_routines(bridge) and renamed.routines[0].name == "My breakfast" and len(minings) == 6
    finally:
        bridge.close()
        store.close()


def test_a_store_without_an_append_mark_keeps_nothing(grown, onto, monkeypatch):
    bridge, logger = grown
    kept = KeptPast()
    monkeypatch.setattr(bridge.store, "append_mark", lambda neem: None)
    question = "what do I usually do after open(fridge)?"
    assert ask(bridge, onto, question, kept=kept).evidence["occurrences"] == 3
    logger.action("open(fridge)", t(1, 8, 2), t(1, 8, 2, 10))
    logger.flush()
    assert ask(bridge, onto, question, kept=kept).evidence["occurrences"] == 4


def test_only_the_answers_that_need_the_actions_read_them_again(grown, onto, monkeypatch):
    """... and read only what was added, where the history cache's rule allows."""
    from oracle.past import kept as kept_module

    bridge, logger = grown
    reads, whole = [], []
    read, history = kept_module._read, kept_module._history
    monkeypatch.setattr(kept_module, "_read", lambda e, b: reads.append(1) or read(e, b))
    monkeypatch.setattr(kept_module, "_history", lambda b: whole.append(1) or history(b))
    kept = KeptPast()
    ask(bridge, onto, "what do I usually do after open(fridge)?", kept=kept)
    ask(bridge, onto, "what do I usually do after open(fridge)?", kept=kept)
    assert len(reads) == 1
    logger.action("open(fridge)", t(1, 8, 2), t(1, 8, 2, 10))
    logger.flush()
    last = ask(bridge, onto, "when did I last open the fridge?", kept=kept).evidence["begin"]
    assert last == pytest.approx(seconds_of(t(1, 8, 2))) and len(reads) == 1  # asked of Prolog alone
    assert ask(bridge, onto, "what do I usually do after open(fridge)?", kept=kept).evidence["occurrences"] == 4
    assert len(reads) == 2 and len(whole) == 1  # the new action read alone


def test_the_words_are_read_once_per_ontology_and_answers_read_with_them_say_the_same(bridge, onto, monkeypatch):
    import oracle.words as words

    kept, reads = KeptPast(), []
    real = words.load_lexicon

    def counted(*args, **kwargs):
        reads.append(1)
        return real(*args, **kwargs)

    fresh = [ask(bridge, onto, question).to_json() for question in QUESTIONS[:6]]
    monkeypatch.setattr(words, "load_lexicon", counted)
    assert [ask(bridge, onto, question, kept=kept).to_json() for question in QUESTIONS[:6]] == fresh
    assert len(reads) == 1
    assert kept.lexicon(onto) is kept.lexicon(onto)
