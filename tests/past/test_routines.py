"""Routines: mined, named, recognised in progress, stored in the NEEM as workflows and read back."""

from __future__ import annotations

import json
import subprocess
import sys
from datetime import datetime

import pytest

from oracle.past.routines import Done, episodes_of, mine_routines, name_of, recognise
from oracle.timeline import seconds_of

BREAKFAST = ("open(fridge)", "pick(milk_carton)", "pour(milk_carton, cereal_bowl)", "place(milk_carton, fridge)",
             "pick(cereal_bowl)", "drink_from(cereal_bowl)", "place(cereal_bowl, kitchen_table)")
COFFEE = ("pick(red_mug)", "place(red_mug, kitchen_table)", "turn_on(coffee_machine)", "turn_off(coffee_machine)",
          "pick(red_mug)", "drink_from(red_mug)", "place(red_mug, kitchen_table)")


def day(n: int, hour: int, calls: tuple[str, ...], minute: int = 0) -> list[Done]:
    start = seconds_of(datetime(2025, 3, 3 + n, hour, minute))
    return [Done(start + 15 * i, start + 15 * i + 10, c) for i, c in enumerate(calls)]


def week(days: int = 5) -> list[Done]:
    done: list[Done] = []
    for n in range(days):
        done += day(n, 7, BREAKFAST, minute=5 * n) + day(n, 15, COFFEE)
    return done + day(2, 20, ("pick(apple)", "eat(apple)"))  # once: no routine


@pytest.mark.parametrize(("steps", "name"), [
    (COFFEE, "Coffee in the red mug"),
    (BREAKFAST, "Milk in the cereal bowl"),
    (("pick(green_mug)", "pick(green_tea_bag)", "place(green_tea_bag, green_mug)", "pick(thermos)",
      "pour(thermos, green_mug)", "drink_from(green_mug)"), "Green tea in the green mug"),
    (("pick(beer_bottle)", "drink_from(beer_bottle)", "place(beer_bottle, fridge)"), "Beer from the bottle"),
    (("pick(bread)", "pick(knife)", "cut(knife, bread)", "eat(bread)"), "Bread"),
    (("open(fridge)", "close(fridge)"), "Open fridge"),
])
def test_names_from_steps_and_objects(steps, name):
    assert name_of(steps) == name


def test_episodes_split_at_idle_gaps():
    episodes = episodes_of(day(0, 7, BREAKFAST) + day(0, 15, COFFEE))
    assert [e.calls for e in episodes] == [BREAKFAST, COFFEE]


def test_mining_finds_the_recurring_chains_with_days_and_usual_time():
    routines = mine_routines(week())
    assert [(r.key, r.name, r.steps, r.days, r.usual_time, r.part) for r in routines] == [
        ("r1", "Milk in the cereal bowl", BREAKFAST, 5, "07:10", "Morning"),
        ("r2", "Coffee in the red mug", COFFEE, 5, "15:00", "Midday")]
    assert mine_routines(week(2)) == []  # two days: nothing recurs on three


def test_a_routine_in_progress_is_recognised_with_what_remains():
    routines = mine_routines(week())
    found = recognise(routines, BREAKFAST[:2], 7.2)
    assert found is not None and found.routine.key == "r1" and found.remaining == BREAKFAST[2:]
    assert recognise(routines, ["pick(apple)", "eat(apple)"], 20.0) is None
    assert recognise(routines, COFFEE[:2], 7.0) is None  # the coffee is not a morning routine


def test_routines_are_stored_as_workflows_and_read_back_through_prolog(routine_store, onto):
    from oracle.bridge import Bridge
    from oracle.past.mine import neem_routines
    from oracle.past.workflows import save_routines, stored_routines
    from oracle.store import open_store

    store = open_store(routine_store, create=False)
    bridge = Bridge(store, "weekly", onto)
    try:
        history = bridge.history()
        found = neem_routines(bridge)
        assert [r.name for r in found.routines] == ["Milk in the cereal bowl", "Coffee in the red mug"]
        assert found.current is not None and found.current.routine.key == "r1"
        assert found.current.remaining == BREAKFAST[3:]
        save_routines(store, onto, "weekly", found.routines, ["r2"])
        stored = stored_routines(bridge)
        assert [(s["name"], tuple(s["steps"]), s["days"], s["by_user"]) for s in stored] == [
            ("Milk in the cereal bowl", BREAKFAST, 4, False), ("Coffee in the red mug", COFFEE, 4, True)]  # day 5: in progress
        rows = bridge.query("findall(S, kb_call(triple(W, soma:hasStep, S), any), Ss), length(Ss, N)")
        assert rows[0]["N"] == len(BREAKFAST) + len(COFFEE)
        assert bridge.history() == history  # the workflows are no actions
    finally:
        bridge.close()
        store.close()


def test_cli_rename_is_kept_when_mined_again(routine_store):
    run = [sys.executable, "-m", "oracle", "routines", "--store", str(routine_store), "--neem", "weekly"]
    subprocess.run([*run, "--rename", "r2", "Afternoon coffee"], capture_output=True, text=True, check=True)
    reply = json.loads(subprocess.run([*run, "--json"], capture_output=True, text=True, check=True).stdout)
    assert [(r["name"], r["named_by_user"]) for r in reply["routines"]] == [
        ("Milk in the cereal bowl", False), ("Afternoon coffee", True)]
    bad = subprocess.run([*run, "--rename", "r7", "x"], capture_output=True, text=True)
    assert bad.returncode == 1 and bad.stderr == "error: no routine 'r7'; the routines are r1, r2\n"


def test_a_persona_s_daily_routine_is_recovered():
    from oracle.evaluation.routines import score_persona
    from oracle.past.routines import MiningSettings
    from oracle.world.personas import make_persona

    score = score_persona(make_persona(0, 21), 7, 0, 5, MiningSettings())
    assert (score.mined, score.truth, score.matched) == (3, 3, 3)
    assert score.runs[2] == score.tried > 0


def _reference_mining(done, settings):
    """mine_routines as first written (each mean over a generator, each similarity from the
    calls): the faster one must find the very same routines."""
    import statistics

    from oracle.past.routines import MiningSettings, Routine, _distinct_names, _hours_apart, jaccard
    from oracle.timeline import time_of_day

    settings = settings or MiningSettings()
    episodes = episodes_of(done)
    clusters, hours = [], []
    for episode in episodes:
        best, best_score = None, settings.min_similarity
        for index, cluster in enumerate(clusters):
            if _hours_apart(episode.hour, hours[index] / len(cluster)) > settings.max_hours:
                continue
            score = statistics.fmean(jaccard(episode.calls, other.calls) for other in cluster)
            if score >= best_score:
                best, best_score = index, score
        if best is None:
            clusters.append([episode])
            hours.append(episode.hour)
        else:
            clusters[best].append(episode)
            hours[best] += episode.hour
    observed = len({e.day for e in episodes})
    kept = [c for c in clusters if len({e.day for e in c}) >= max(settings.min_days, settings.min_share * observed)]
    kept.sort(key=lambda c: statistics.median(e.hour for e in c))
    routines = []
    for i, cluster in enumerate(kept, start=1):
        medoid = max(cluster, key=lambda e: (statistics.fmean(jaccard(e.calls, o.calls) for o in cluster), -e.begin))
        hour = statistics.median(e.hour for e in cluster)
        routines.append(Routine(f"r{i}", name_of(medoid.calls), medoid.calls, len({e.day for e in cluster}), hour,
                                time_of_day(hour), tuple(e.begin for e in cluster), tuple(e.calls for e in cluster)))
    return _distinct_names(routines)


@pytest.mark.parametrize("seed", range(12))
def test_mining_equals_the_reference_reading(seed):
    import random

    from oracle.past.routines import MiningSettings

    rng = random.Random(seed)
    calls = BREAKFAST + COFFEE + ("pick(apple)", "eat(apple)", "open(fridge)", "close(fridge)")
    done: list[Done] = []
    mined: list[int] = []
    usual = [(7, BREAKFAST), (15, COFFEE), (rng.randint(9, 21), tuple(rng.choice(calls) for _ in range(5)))]
    for n in range(rng.randint(3, 12)):  # the usual chains, most days, a step or two changed; and one of chance
        episodes = [(hour + rng.choice((-1, 0, 1)), tuple(c if rng.random() > 0.2 else rng.choice(calls) for c in steps))
                    for hour, steps in usual if rng.random() < 0.8]
        episodes.append((rng.randint(6, 22), tuple(rng.choice(calls) for _ in range(rng.randint(1, 8)))))
        for hour, steps in sorted(episodes):
            done += day(n, hour, steps, minute=rng.randint(0, 40))
    for settings in (None, MiningSettings(min_similarity=0.3, min_days=2), MiningSettings(max_hours=4.0)):
        found = mine_routines(done, settings)
        assert found == _reference_mining(done, settings)
        mined.append(len(found))
    assert any(mined)
