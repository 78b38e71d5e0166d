import re
import subprocess
import sys
from collections import defaultdict

import pytest
import yaml

from oracle.chains import read_chains
from oracle.errors import NeemOracleError
from oracle.world.generate import INTENTIONS, generate
from oracle.world.personas import make_persona, make_personas, tune_count
from oracle.world.worldfile import load_world


@pytest.fixture(scope="module")
def world():
    return load_world()


@pytest.fixture(scope="module")
def bench(tmp_path_factory, world):
    out = tmp_path_factory.mktemp("bench")
    summary = generate(out, personas=12, days=3, seed=7, world=world)
    return out, summary


def test_split_is_17_of_105_like_the_thesis():
    people = make_personas(105, seed=3)
    assert tune_count(105) == 17
    assert [p.split for p in people].count("tune") == 17
    assert [p.split for p in people].count("test") == 88
    assert len({p.file_name for p in people}) == 105
    # the user id of the chains is also the NEEM id: letters, digits and '-'
    assert all(re.fullmatch(r"[A-Za-z0-9][A-Za-z0-9-]{0,63}", p.file_name) for p in people)


def test_personas_have_the_appendix_b_shape_and_known_intentions():
    for index in range(30):
        persona = make_persona(5, index).to_yaml()
        assert {"file_name", "persona", "daily_routine", "variations"} <= set(persona)
        assert persona["daily_routine"] and persona["variations"]
        for entry in persona["daily_routine"] + persona["variations"]:
            assert set(entry) == {"description", "time", "intention"}
            assert entry["intention"] in INTENTIONS
        hours = [e["time"] for e in persona["daily_routine"]]
        assert hours == sorted(hours)


def test_personas_differ_in_preferences():
    people = make_personas(105, seed=1)
    assert len({p.preferences.mug for p in people}) == 3
    assert {p.preferences.hot_drink for p in people} == {"tea", "coffee", "none"}
    assert len({(p.preferences.mug, p.preferences.breakfast, p.preferences.snacks) for p in people}) > 60


def test_every_generated_step_is_feasible_and_in_its_available_set(bench, world):
    out, summary = bench
    rows = list(read_chains(out / "tune.jsonl")) + list(read_chains(out / "test.jsonl"))
    assert len(rows) == summary.actions
    by_user = defaultdict(list)
    for row in rows:
        by_user[row.user].append(row)
    assert len(by_user) == 12
    for user_rows in by_user.values():
        state, day = None, None
        for row in user_rows:
            if row.time.date() != day:  # the kitchen is tidied overnight
                state, day = world.initial_state(), row.time.date()
            assert row.available == world.available(state)
            assert row.action in row.available
            state = world.apply(state, row.action)


def test_times_increase_and_start_near_routine_hours(bench):
    out, _ = bench
    personas = {p["file_name"]: p for p in yaml.safe_load((out / "personas.yaml").read_text())["personas"]}
    by_user = defaultdict(list)
    for row in read_chains(out / "test.jsonl"):
        by_user[row.user].append(row)
    for user, rows in by_user.items():
        times = [r.time for r in rows]
        assert times == sorted(times)
        gaps = [(b - a).total_seconds() for a, b in zip(times, times[1:]) if a.date() == b.date()]
        assert min(gaps) >= 3
        entries = personas[user]["daily_routine"] + personas[user]["variations"]
        hours = [int(str(e["time"]).split(":")[0]) + int(str(e["time"]).split(":")[1]) / 60 for e in entries]
        first = rows[0].time.hour + rows[0].time.minute / 60
        assert min(abs(first - h) for h in hours) < 1.0


def test_same_seed_same_benchmark_other_seed_other_benchmark(tmp_path, world):
    generate(tmp_path / "a", personas=3, days=2, seed=11, world=world)
    generate(tmp_path / "b", personas=3, days=2, seed=11, world=world)
    generate(tmp_path / "c", personas=3, days=2, seed=12, world=world)
    for name in ("personas.yaml", "tune.jsonl", "test.jsonl"):
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes()
    assert (tmp_path / "a" / "test.jsonl").read_bytes() != (tmp_path / "c" / "test.jsonl").read_bytes()


def test_days_are_not_all_the_same(bench):
    out, _ = bench
    by_day = defaultdict(list)
    for row in read_chains(out / "test.jsonl"):
        by_day[(row.user, row.time.date())].append(str(row.action))
    users = {user for user, _ in by_day}
    varied = sum(1 for user in users if len({tuple(v) for (u, _), v in by_day.items() if u == user}) > 1)
    assert varied == len(users)


def test_bad_arguments_are_user_errors(tmp_path):
    with pytest.raises(NeemOracleError, match="at least one persona"):
        generate(tmp_path, personas=0)


def test_cli_generate(tmp_path):
    result = subprocess.run(
        [sys.executable, "-m", "oracle", "generate", "--personas", "2", "--days", "1", "--seed", "4", "--out", str(tmp_path)],
        capture_output=True, text=True, timeout=120,
    )
    assert result.returncode == 0, result.stderr
    assert "available per step" in result.stdout
    assert (tmp_path / "test.jsonl").exists() and (tmp_path / "personas.yaml").exists()


def test_modes_say_who_did_each_row_and_change_nothing_else(tmp_path, world):
    import json

    generate(tmp_path / "plain", personas=2, days=2, seed=5, world=world)
    generate(tmp_path / "modes", personas=2, days=2, seed=5, world=world, modes=True)
    for name in ("tune.jsonl", "test.jsonl"):
        plain = [json.loads(line) for line in (tmp_path / "plain" / name).read_text().splitlines()]
        modes = [json.loads(line) for line in (tmp_path / "modes" / name).read_text().splitlines()]
        assert [{k: v for k, v in row.items() if k != "performed_by"} for row in modes] == plain
        assert {row["performed_by"] for row in modes} <= {"user", "robot", "together"}
    assert (tmp_path / "plain" / "personas.yaml").read_bytes() == (tmp_path / "modes" / "personas.yaml").read_bytes()
