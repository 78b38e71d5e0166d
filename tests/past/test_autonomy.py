"""Who performs an action: the persona's autonomy profile and the predictor of the usual mode."""

from __future__ import annotations

from oracle.past.autonomy import ModeCounts, Performed, fit
from oracle.world.autonomy import autonomy_profile, modes_of
from oracle.world.personas import make_persona


def test_the_most_specific_context_decides():
    model = fit([Performed("pour(thermos, red_mug)", "Morning", "robot")] * 2
                + [Performed("pour(milk_carton, red_mug)", "Morning", "user")] * 3
                + [Performed("pour(thermos, red_mug)", "Evening", "user")])
    assert model.predict("pour(thermos, red_mug)", "Morning") == ("robot", "call and part")
    assert model.predict("pour(milk_carton, red_mug)", "Evening") == ("user", "call")
    assert model.predict("pour(juice, red_mug)", "Morning") == ("user", "task and part")
    assert ModeCounts().predict("pick(apple)", "Morning") == ("user", "none")  # nothing seen: the user's


def test_a_weak_grip_leaves_pouring_to_the_robot():
    weak = next(p for p in (make_persona(0, i) for i in range(60)) if "weak grip" in p.persona)
    profile = autonomy_profile(weak, 0)
    assert profile.by_hand("pour", ("thermos", "red_mug"), 20.0) < profile.by_hand("pour", ("thermos", "red_mug"), 9.0)
    assert profile.by_hand("pour", ("thermos", "red_mug"), 9.0) < 0.5 < profile.by_hand("eat", ("apple",), 9.0)


def test_modes_are_a_pure_function_of_seed_and_persona():
    from oracle.world.generate import simulate
    from oracle.world.worldfile import load_world

    persona = make_persona(0, 4)
    rows, _ = simulate(persona, load_world(), 2, 0)
    assert modes_of(persona, rows, 0) == modes_of(persona, rows, 0)
    assert set(modes_of(persona, rows, 0)) == {"user", "robot", "together"}


def test_together_is_likeliest_where_the_grip_is_the_obstacle():
    weak = next(p for p in (make_persona(0, i) for i in range(60)) if "weak grip" in p.persona)
    profile = autonomy_profile(weak, 0)
    pour = profile.odds("pour", ("thermos", "red_mug"), 9.0)
    assert abs(sum(pour.values()) - 1.0) < 1e-9 and pour["together"] > 0
    eat = profile.odds("eat", ("apple",), 9.0)
    # shared less where neither a grip nor a heavy object is the obstacle
    assert eat["together"] / (1 - eat["user"]) < pour["together"] / (1 - pour["user"])
    assert profile.likeliest("eat", ("apple",), 9.0) == "user"


def test_three_modes_and_the_tie_leaves_the_user_the_most_to_do():
    from collections import Counter

    from oracle.past.autonomy import majority

    model = fit([Performed("pour(thermos, red_mug)", "Morning", "together")] * 2
                + [Performed("pour(thermos, red_mug)", "Morning", "robot")])
    assert model.predict("pour(thermos, red_mug)", "Morning") == ("together", "call and part")
    usual = model.usual("pour(thermos, red_mug)", "Morning")
    assert usual.to_json() == {"mode": "together", "context": "call and part",
                               "counts": {"robot": 1, "user": 0, "together": 2}}
    assert majority(Counter({"robot": 2, "together": 2})) == "together"
    assert majority(Counter({"robot": 2, "together": 2, "user": 2})) == "user"
    assert majority(Counter({"robot": 3, "together": 2})) == "robot"
    assert ModeCounts().usual("pick(apple)", "Morning").mode is None  # nothing known: no mode said


def test_together_is_written_with_both_performers_and_read_back(tmp_path):
    """An action performed together: both agents are its performers, each with an agent role
    of its task during it (neem-interface's participant with a role); the call reads back as
    it was logged (agent roles are no arguments, with objects or without) and ``ask`` and the
    history rows (odb_history:action_modes/2) name the mode."""
    import shutil
    from datetime import datetime

    import pytest

    if shutil.which("swipl") is None:
        pytest.skip("SWI-Prolog (swipl) is not installed")
    from oracle.bridge import Bridge
    from oracle.neem import terms as T
    from oracle.neem.writer import NeemLogger
    from oracle.ontology import build_ontology
    from oracle.past.ask import ask
    from oracle.past.autonomy import modes_from_rows
    from oracle.store import open_store
    from oracle.timeline import seconds_of

    onto = build_ontology()
    store = open_store(tmp_path / "s.sqlite")
    log = NeemLogger.create(store, onto, user="sam", neem_id="duo")
    at = lambda minute: datetime(2025, 3, 3, 8, minute)  # noqa: E731
    log.action("pour(thermos, red_mug)", at(0), at(1), performed_by="together")
    log.action("open_fridge", at(2), at(3), performed_by="together")
    log.action("pour(thermos, red_mug)", at(4), at(5), performed_by="together")
    done = log.action("pour(thermos, red_mug)", at(6), at(7), performed_by="user")
    log.action("pick(apple)", at(8), at(9))
    log.flush()
    performers = sorted(d["o"] for d in store.find(log.neem_id, p=T.PERFORMED_BY, exact=True) if d["s"] == done.iri)
    assert len(performers) == 1 and "robot" not in performers[0]
    bridge = Bridge(store, log.neem_id, onto)
    try:
        assert [row["call"].replace(",", ", ") for row in bridge.history() if row["call"] != "idle"] == [
            "pour(thermos, red_mug)", "open_fridge", "pour(thermos, red_mug)", "pour(thermos, red_mug)", "pick(apple)"]
        answer = ask(bridge, onto, "who usually does pour(thermos, red_mug)?")
        assert answer.evidence["counts"] == {"user": 1, "robot": 0, "together": 2, "unknown": 0}
        assert answer.english == "You usually pour the coffee into the red mug together with the robot (2 of 3 times)."
        rows = bridge.history()
        assert [row["mode"] for row in rows if row["call"] != "idle"] == ["together", "together", "together", "user",
                                                                          "robot"]
        modes = modes_from_rows(rows)
        assert modes.predict("open_fridge", "Morning") == ("together", "call and part")
        assert modes.predict("pick(apple)", "Morning") == ("robot", "call and part")
        assert modes_from_rows([row for row in rows if row["begin"] <= seconds_of(at(3))]).usual(
            "pour(thermos, red_mug)", "Morning").counts == {"robot": 0, "user": 0, "together": 1}
    finally:
        bridge.close()
        store.close()


def test_a_mode_no_one_knows_is_a_one_line_error_and_writes_nothing(tmp_path):
    import pytest

    from oracle.chains import parse_row
    from oracle.errors import ChainSyntaxError, LoggingError
    from oracle.neem.writer import NeemLogger
    from oracle.ontology import build_ontology
    from oracle.store import open_store

    with pytest.raises(ChainSyntaxError, match=r"^f.jsonl:3: performed_by must be one of robot, user, together, got 'both'$"):
        parse_row({"user": "u", "action": "pick(apple)", "performed_by": "both"}, "f.jsonl:3")
    store = open_store(tmp_path / "s.sqlite")
    log = NeemLogger.create(store, build_ontology(), user="sam", neem_id="bad")
    log.flush()
    before = len(list(store.find(log.neem_id)))
    with pytest.raises(LoggingError, match="performed_by must be one of robot, user, together, got 'ROBOT'"):
        log.action("pick(apple)", 1_740_988_800, performed_by="ROBOT")
    log.flush()
    assert len(list(store.find(log.neem_id))) == before
    store.close()
