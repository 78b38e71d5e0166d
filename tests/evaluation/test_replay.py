import json
from datetime import datetime, timedelta

import pytest

from oracle.algorithm.params import Hyperparameters
from oracle.algorithm.records import Option, Step
from oracle.cli import main
from oracle.errors import OntologyError
from oracle.evaluation.baselines import BASELINES, Bigram, MostFrequent, NGram, chance_hit
from oracle.evaluation.replay import (LEGACY, OracleMethod, ReplayRules, check_users, decision_time, load_users, replay,
                                      summarize)
from oracle.timeline import IDLE_THRESHOLD_S
from oracle.ontology import build_ontology


@pytest.fixture(scope="module")
def kitchen():
    return build_ontology()


def write_chain(path, user, actions, available=None, start=datetime(2026, 3, 2, 8, 0), gap=10):
    with path.open("a") as handle:
        t = start
        for action in actions:
            row = {"user": user, "time": t.isoformat(), "action": action}
            if available is not None:
                row["available"] = available
            handle.write(json.dumps(row) + "\n")
            t += timedelta(seconds=gap)


def step(label):
    return Step(task=label, label=label)


def test_baselines_rank_by_counts():
    a, b, c = Option("a"), Option("b"), Option("c")
    mf, bi, ng = MostFrequent(), Bigram(), NGram()
    for method in (mf, bi, ng):
        for t in ["a", "b", "a", "c", "a", "b"]:
            method.observe(Step(t))
    assert mf.rank([c, b, a]) == [a, b, c]
    # after "b" came "a" once; after "a" came b twice and c once
    assert bi.rank([c, b, a])[0] == a
    assert ng.rank([a, b, c])[0] == a


def test_chance_is_exact():
    assert chance_hit(1, 4, True) == 0.25 and chance_hit(5, 4, True) == 1.0 and chance_hit(1, 4, False) == 0.0


def test_replay_learns_a_routine_and_beats_chance(tmp_path, kitchen):
    routine = ["open(small_drawer)", "pick(red_mug)", "place(red_mug)", "close(small_drawer)", "pick(thermos)",
               "pour(thermos, red_mug)", "place(thermos)"]
    available = sorted(set(routine + ["pick(banana)", "eat(banana)", "open(fridge)", "pick(blue_mug)"]))
    path = tmp_path / "c.jsonl"
    for day in range(6):
        write_chain(path, "ada", routine, available, start=datetime(2026, 3, 2 + day, 8, 0))
    users = load_users(path)
    result = replay(kitchen, users, [OracleMethod(kitchen, Hyperparameters()), Bigram()])
    summary = summarize(result)
    assert summary["n_predictions"] == 42
    assert summary["methods"]["oracle"]["top3"] > summary["chance"]["top3"] + 0.3
    last_day = [o for o in result.outcomes if o.index >= 35]
    assert all(o.ranks["oracle"] <= 5 for o in last_day)
    assert sum(o.ranks["oracle"] == 1 for o in last_day) >= 4


def test_missing_available_offers_what_the_user_did_before_or_the_vocabulary_as_an_option(tmp_path, kitchen):
    path = tmp_path / "c.jsonl"
    write_chain(path, "bo", ["pick(red_mug)", "place(red_mug)", "pick(red_mug)", "pick(apple)"])
    honest = replay(kitchen, load_users(path), [MostFrequent()])
    # never a future action: a first use is not offered, and every method misses it
    assert [o.n_candidates for o in honest.outcomes] == [0, 1, 2, 2]
    assert [o.truth_offered for o in honest.outcomes] == [False, False, True, False]
    assert [o.ranks["most_frequent"] for o in honest.outcomes] == [None, None, 1, None]
    old = replay(kitchen, load_users(path), [MostFrequent()], protocol=ReplayRules("vocabulary", "start", False))
    assert [o.n_candidates for o in old.outcomes] == [3, 3, 3, 3]


def test_decision_time_never_reads_the_true_start_beyond_the_gap():
    assert decision_time(None, 1000.0, "previous-end") is None  # a user's first action: no clock yet
    assert decision_time(990.0, 1000.0, "previous-end") == 990.0
    assert decision_time(900.0, 5000.0, "previous-end") == 900.0 + IDLE_THRESHOLD_S  # the gap became one
    assert decision_time(900.0, 5000.0, "previous-end") == decision_time(900.0, 9000.0, "previous-end")
    assert decision_time(900.0, 5000.0, "start") == 5000.0
    with pytest.raises(ValueError, match="candidates"):
        ReplayRules("future")


class Clocked(MostFrequent):
    """Records the decision times and parts of day it is asked at."""

    def reset(self):
        super().reset()
        self.asked = []

    def rank(self, candidates, time_of_day=None, at=None):
        self.asked.append((at, time_of_day))
        return super().rank(candidates, time_of_day, at)


def test_the_replay_ranks_at_the_decision_time_of_its_rules(tmp_path, kitchen):
    path = tmp_path / "c.jsonl"
    actions = ["pick(red_mug)", "place(red_mug)", "pick(red_mug)"]
    write_chain(path, "bo", actions, available=actions, start=datetime(2026, 3, 2, 10, 59, 0), gap=600)
    clocked = Clocked()
    replay(kitchen, load_users(path), [clocked])
    start = datetime(2026, 3, 2, 10, 59, 0).timestamp()
    # rows have no end: the previous action ends when it starts; gaps of 600 s are idle gaps
    assert [at for at, _ in clocked.asked] == [None, start + 20, start + 620]
    assert [tod for _, tod in clocked.asked] == [None, "Morning", "Midday"]
    replay(kitchen, load_users(path), [clocked], protocol=LEGACY)
    assert [at for at, _ in clocked.asked] == [start, start + 600, start + 1200]


def test_unknown_object_is_reported_with_line(tmp_path, kitchen):
    path = tmp_path / "c.jsonl"
    write_chain(path, "bo", ["pick(red_mug)", "pick(unicorn)"])
    with pytest.raises(OntologyError, match=r"c\.jsonl:2: unknown object 'unicorn'"):
        check_users(kitchen, load_users(path), str(path))


def test_evaluate_command_writes_json_report_and_plots(tmp_path, capsys):
    path = tmp_path / "c.jsonl"
    for day in range(3):
        write_chain(path, "cy", ["pick(apple)", "eat(apple)", "pick(red_mug)", "drink_from(red_mug)"],
                    start=datetime(2026, 3, 2 + day, 19, 0))
    out = tmp_path / "out"
    code = main(["evaluate", str(path), "--baselines", "--ablations", "--json", str(out / "s.json"),
                 "--report", str(out / "r.md"), "--plots", str(out)])
    assert code == 0
    summary = json.loads((out / "s.json").read_text())
    reference = next(iter(summary["methods"]))
    assert reference == summary["method"] == "personal"  # the default
    assert set(BASELINES) | {"personal", "oracle", "pop_ppm"} <= set(summary["methods"])
    assert set(summary["chance"]) == {"top1", "top3", "top5"} and summary["n_predictions"] == 12
    # the four first uses of day one are offered nothing (honest candidates); the rest are all in the top 5
    assert summary["methods"]["oracle"]["per_user"]["cy"]["top5"] == 8 / 12 and summary["truth_not_offered"] == 4
    assert summary["protocol"] == {"candidates": "history", "decision": "previous-end", "served": True}
    # every other method is compared with the first one, on the same predictions
    paired = summary["comparisons"]
    assert paired["reference"] == reference and set(paired["methods"]) == set(summary["methods"]) - {reference}
    ngram = paired["methods"]["ngram"]["top1"]
    assert ngram["low"] <= ngram["difference"] <= ngram["high"] and 0 <= ngram["p"] <= ngram["p_holm"] <= 1
    cold = summary["cold_start"]
    assert cold["n_predictions"] == 12 and cold["comparisons"]["reference"] == reference
    ablations = summary["ablations"]["settings"]
    assert set(ablations) == set("ABCDEFGHIJKLMN") and "vs_A" in ablations["B"] and "vs_A" not in ablations["A"]
    report = (out / "r.md").read_text()
    assert "| oracle |" in report and "Paired differences against" in report and "## Cold start" in report
    assert "| ngram | " + f"{100 * ngram['difference']:+.1f} [" in report
    for name in ("per_user_box.png", "learning_curve.png", "differences.png", "ablations.png"):
        assert (out / name).stat().st_size > 1000


def test_evaluate_rejects_bad_settings(tmp_path, capsys):
    path = tmp_path / "c.jsonl"
    write_chain(path, "cy", ["pick(apple)"])
    assert main(["evaluate", str(path), "--settings", "Z"]) == 1
    assert "not a YAML file" in capsys.readouterr().err


def test_evaluate_method_thesis_scores_the_thesis_oracle_alone_with_its_figures(tmp_path, kitchen):
    path = tmp_path / "c.jsonl"
    for day in range(3):
        write_chain(path, "cy", ["pick(apple)", "eat(apple)", "pick(red_mug)", "drink_from(red_mug)", "pick(banana)"],
                    start=datetime(2026, 3, 2 + day, 19, 0))
    assert main(["evaluate", str(path), "--method", "thesis", "--json", str(tmp_path / "t.json")]) == 0
    thesis = json.loads((tmp_path / "t.json").read_text())
    assert list(thesis["methods"]) == ["oracle"] and thesis["method"] == "oracle"
    direct = summarize(replay(kitchen, load_users(path), [OracleMethod(kitchen, Hyperparameters())]))
    for k in ("top1", "top3", "top5"):
        assert thesis["methods"]["oracle"][k] == direct["methods"]["oracle"][k]
    assert main(["evaluate", str(path), "--json", str(tmp_path / "r.json")]) == 0
    assert list(json.loads((tmp_path / "r.json").read_text())["methods"]) == ["personal"]
