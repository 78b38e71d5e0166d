"""Action logs without clock times (EGTEA Gaze+): refused by default with a one-line error, logged
in file order on the sequence clock with ``import --no-clock``, and ranked as the replay ranks them."""

from __future__ import annotations

import json
import shutil
from datetime import datetime
from pathlib import Path

import pytest

from oracle.store.ids import resolve_neem
from oracle.cli import main
from oracle.errors import LoggingError
from oracle.store import RDF_TYPE, open_store

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "docs" / "examples"
ONTOLOGY = ["--odb", str(EXAMPLES / "odb"), "--mapping", str(EXAMPLES / "mapping.yaml")]
ACTIONS = ["pick(teapot)", "pour(teapot, mug)", "put_down(teapot)", "pick(mug)", "drink_from(mug)",
           "put_down(mug)", "pick(teapot)", "pour(teapot, mug)", "put_down(teapot)", "pick(mug)"]
needs_prolog = pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed")


def timeless(tmp_path: Path, rows: list[dict] | None = None) -> Path:
    path = tmp_path / "timeless.jsonl"
    rows = rows if rows is not None else [{"user": "ada", "action": a, "session": "s1"} for a in ACTIONS]
    path.write_text("".join(json.dumps(row) + "\n" for row in rows))
    return path


def test_a_timeless_log_is_refused_without_no_clock_and_creates_nothing(tmp_path, capsys):
    store = tmp_path / "s.sqlite"
    assert main(["import", str(timeless(tmp_path)), "--store", str(store), *ONTOLOGY]) == 1
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "'time' is required" in err and "--no-clock" in err
    assert not store.exists()


def test_no_clock_refuses_a_row_with_a_time_and_writes_nothing(tmp_path, capsys):
    rows = [{"user": "ada", "action": "pick(mug)"}, {"user": "ada", "time": "2026-03-02T07:30:00", "action": "pick(teapot)"}]
    store = tmp_path / "s.sqlite"
    assert main(["import", str(timeless(tmp_path, rows)), "--store", str(store), "--no-clock", *ONTOLOGY]) == 1
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and ":2:" in err and "has a time" in err
    assert not store.exists()


def test_no_clock_logs_each_user_in_file_order_on_positions(tmp_path, capsys):
    from oracle.neem import terms as T
    from oracle.neem.query import executed_actions

    spec = str(tmp_path / "s.sqlite")
    rows = [{"user": u, "action": a} for a in ACTIONS[:4] for u in ("ada", "bo")]
    assert main(["import", str(timeless(tmp_path, rows)), "--store", spec, "--no-clock", *ONTOLOGY]) == 0
    assert [line.split("\t", 1)[1] for line in capsys.readouterr().out.splitlines()] == ["ada\t4 actions", "bo\t4 actions"]
    store = open_store(spec)
    ada, bo = resolve_neem(store, "ada"), resolve_neem(store, "bo")
    assert store.neem(ada).meta["clock"] == "sequence"
    spans = [(a.begin, a.end) for a in executed_actions(store, ada)]
    assert spans == [(0.0, 1.0), (1.0, 2.0), (2.0, 3.0), (3.0, 4.0)]  # each action meets the next: no idle
    intervals = {d["s"] for d in store.find(ada, p=RDF_TYPE, o=T.TIME_INTERVAL, exact=True)}
    types = {d["o"] for d in store.find(ada, p=RDF_TYPE) if d["s"] in intervals}
    assert types == {T.TIME_INTERVAL}  # no odb:TimeOfDay part: the log has no clock
    assert main(["neems", "--store", spec, "--json"]) == 0
    listed = {row["id"]: (row["begin"], row["end"]) for row in json.loads(capsys.readouterr().out)}
    assert listed[bo] == ("position 0", "position 4")


def test_a_neem_without_a_clock_refuses_clock_times_and_keeps_what_it_has(tmp_path):
    from oracle.neem.query import count_actions
    from oracle.neem.writer import NeemLogger
    from oracle.ontology import build_ontology

    spec = str(tmp_path / "s.sqlite")
    assert main(["import", str(timeless(tmp_path)), "--store", spec, "--no-clock", *ONTOLOGY]) == 0
    store = open_store(spec)
    ada = resolve_neem(store, "ada")
    before = count_actions(store, ada)
    onto = build_ontology(EXAMPLES / "odb", EXAMPLES / "mapping.yaml")
    logger = NeemLogger(store, onto, ada)
    with pytest.raises(LoggingError, match="has no clock"):
        logger.action("pick(mug)", datetime(2026, 3, 2, 8, 0))
    logger.close()
    assert count_actions(store, ada) == before


@needs_prolog
def test_rank_of_a_no_clock_neem_is_the_replay_of_the_same_rows(tmp_path, capsys):
    """The NEEM read back through Prolog gives the predictor the very history the replay builds
    from the time-less rows (no part of the day, no idle steps), so the rankings agree."""
    from oracle.algorithm.params import Hyperparameters
    from oracle.algorithm.predictors import DEFAULT, make_predictor
    import dataclasses

    from oracle.calls import DoneBefore, opening_tasks, option_of, step_of
    from oracle.chains import parse_call
    from oracle.ontology import build_ontology

    spec = str(tmp_path / "s.sqlite")
    assert main(["import", str(timeless(tmp_path)), "--store", spec, "--no-clock", *ONTOLOGY]) == 0
    offered = ["pick(teapot)", "pick(mug)", "drink_from(mug)", "put_down(mug)"]
    capsys.readouterr()
    assert main(["rank", "--store", spec, "--neem", "ada", "--no-write", "--json", "--available", *offered]) == 0
    ranked = json.loads(capsys.readouterr().out)
    assert ranked["time_of_day"] is None and ranked["at"] == len(ACTIONS) and ranked["history"] == len(ACTIONS)

    onto = build_ontology(EXAMPLES / "odb", EXAMPLES / "mapping.yaml")
    # each step offered what was done before it, as the history read gives it (calls.DoneBefore):
    # the default learns from those decisions
    steps, done = [], DoneBefore()
    for a in ACTIONS:
        step = step_of(onto, parse_call(a))
        steps.append(dataclasses.replace(step, options=done.offer()))
        done.add(step.option)
    model = make_predictor(DEFAULT, onto.distances(), opening_tasks(onto), Hyperparameters()).fit(steps)
    expected = model.rank([option_of(onto, parse_call(c)) for c in offered], None)
    assert [row["call"] for row in ranked["ranking"]] == [str(onto_call) for onto_call in _calls(onto, expected)]

    assert main(["rank", "--store", spec, "--neem", "ada", "--no-write", "--available", *offered]) == 0
    assert f"decision at position {len(ACTIONS)} (no clock)" in capsys.readouterr().out


def _calls(onto, ranking):  # noqa: ANN001, ANN202 - test helper
    from oracle.calls import call_of

    return [call_of(onto, t.option) for t in ranking]


def test_a_dump_keeps_the_neem_without_a_clock(tmp_path):
    spec, other = str(tmp_path / "s.sqlite"), str(tmp_path / "t.sqlite")
    assert main(["import", str(timeless(tmp_path)), "--store", spec, "--no-clock", *ONTOLOGY]) == 0
    assert main(["export", "--store", spec, "--neem", "ada", "--out", str(tmp_path / "dump")]) == 0
    assert main(["load", str(tmp_path / "dump"), "--store", other]) == 0
    ada = resolve_neem(open_store(spec), "ada")
    assert open_store(other).neem(ada).meta["clock"] == "sequence"  # the same id, the same clock
