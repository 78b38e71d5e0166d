"""The oracle in the system: history from the NEEM through the Prolog bridge, ranking written back."""

import json
import shutil
from pathlib import Path

import pytest

from oracle.cli import main
from oracle.store import open_store

pytestmark = pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed; run make setup")

CHAIN = [
    "open(small_drawer)", "pick(red_mug)", "place(red_mug, counter_top)", "close(small_drawer)",
    "pick(thermos)", "pour(thermos, red_mug)", "place(thermos, counter_top)",
]


@pytest.fixture()
def store(tmp_path):
    rows = []
    available = sorted(set(CHAIN + ["pick(banana)", "open(fridge)"]))
    for day in range(3):
        for i, action in enumerate(CHAIN):
            rows.append({"user": "ada", "time": f"2026-03-0{2 + day}T08:00:{8 * i:02d}", "duration": 5,
                         "action": action, "available": available})
    chains = tmp_path / "c.jsonl"
    chains.write_text("".join(json.dumps(r) + "\n" for r in rows))
    path = tmp_path / "s.sqlite"
    assert main(["import", str(chains), "--store", str(path)]) == 0
    return path


def test_rank_latest_situation_writes_preference_that_prolog_reads(store, capsys):
    capsys.readouterr()
    assert main(["rank", "--store", str(store), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["history"] == 22  # 3 days x 7 actions + 2 idle delimiters, minus the ranked decision's action
    assert "place(thermos, counter_top)" in [r["call"] for r in out["ranking"][:3]]
    assert [r["rank"] for r in out["ranking"]] == list(range(1, len(out["ranking"]) + 1))
    assert out["written"].startswith("https://ontology.dlr.de/soma/odb#PreferenceOrder")
    assert main(["what-next", "--store", str(store), "--json"]) == 0
    answer = json.loads(capsys.readouterr().out)
    assert "place(thermos,counter_top)" in json.dumps(answer).replace(" ", "")


def test_rank_given_options_without_write(store, capsys):
    capsys.readouterr()
    code = main(["rank", "--store", str(store), "--available", "pick(red_mug)", "open(small_drawer)",
                 "--at", "2026-03-05T08:00:00", "--no-write", "--json"])
    assert code == 0
    out = json.loads(capsys.readouterr().out)
    assert out["ranking"][0]["call"] == "open(small_drawer)" and out["written"] is None


def imported(rows: list[dict[str, object]], tmp_path, capsys) -> Path:
    """``rows`` written as a chains file and imported into a new store (its path; output swallowed)."""
    chains = tmp_path / "c.jsonl"
    chains.write_text("".join(json.dumps(r) + "\n" for r in rows))
    path = tmp_path / "s.sqlite"
    assert main(["import", str(chains), "--store", str(path)]) == 0
    capsys.readouterr()
    return path


def test_a_neem_that_imagined_nothing_ranks_the_actions_done_so_far(tmp_path, capsys):
    """An import of chains without available sets (a sensor home's log) has no imagined
    situation: rank offers what the user did, and what-next reads the ranking it wrote."""
    rows = [{"user": "ada", "time": f"2026-03-0{2 + day}T08:00:{8 * i:02d}", "duration": 5, "action": action}
            for day in range(3) for i, action in enumerate(CHAIN)]
    path = imported(rows, tmp_path, capsys)
    assert main(["rank", "--store", str(path), "--at", "2026-03-05T08:00:00", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert sorted(r["call"] for r in out["ranking"]) == sorted(CHAIN)
    assert out["ranking"][0]["call"] == "open(small_drawer)"           # what every morning began with
    assert out["note"].startswith("no imagined situation in the NEEM: ranked the 7 actions done so far")
    assert out["written"] is not None
    assert main(["what-next", "--store", str(path), "--json"]) == 0
    assert "open(small_drawer)" in capsys.readouterr().out
    # a decision in the past is offered what was done before it
    assert main(["rank", "--store", str(path), "--at", "2026-03-02T08:00:20", "--no-write", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert sorted(r["call"] for r in out["ranking"]) == sorted(CHAIN[:3])


def test_a_neem_without_actions_or_situations_has_nothing_to_rank(tmp_path, capsys):
    from oracle.neem.writer import NeemLogger
    from oracle.ontology import build_ontology
    from oracle.store import open_store

    path = tmp_path / "s.sqlite"
    store = open_store(path)
    NeemLogger.create(store, build_ontology(), user="ada", neem_id="empty").flush()
    store.close()
    capsys.readouterr()
    assert main(["rank", "--store", str(path), "--neem", "empty", "--no-write"]) == 1
    err = capsys.readouterr().err
    assert "has no imagined situation and no action to rank; give the available calls" in err
    assert len(err.strip().splitlines()) == 1


def test_rank_rejects_unknown_objects(store, capsys):
    assert main(["rank", "--store", str(store), "--available", "pick(unicorn)"]) == 1
    assert "unknown object 'unicorn'" in capsys.readouterr().err


def test_rank_and_why_not_with_an_ontology_file(store, tmp_path, capsys):
    owl = tmp_path / "odb.owl"
    assert main(["ontology", "build", "--out", str(owl)]) == 0
    capsys.readouterr()
    assert main(["rank", "--store", str(store), "--ontology", str(owl), "--no-write", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["ranking"]
    assert main(["why-not", "pick(banana)", "--store", str(store), "--ontology", str(owl), "--json"]) == 0
    assert "reasons" in json.loads(capsys.readouterr().out)
    assert main(["why-not", "pick(banana)", "--store", str(store), "--ontology", str(owl), "--odb", str(tmp_path)]) == 1
    assert "either --ontology or --odb/--mapping" in capsys.readouterr().err


def test_the_predicted_chain_goes_on_with_what_is_feasible_after_each_step(tmp_path, capsys):
    # after open(small_drawer) the user picked the red mug three mornings, then the mug was no longer
    # offered after it and the user picked the banana twice; each morning ended with the drawer closed
    rows = []
    for day in range(5):
        picked = "pick(red_mug)" if day < 3 else "pick(banana)"
        steps = (("open(small_drawer)", ["open(small_drawer)", "open(fridge)"]), (picked, [picked, "close(small_drawer)"]),
                 ("close(small_drawer)", ["close(small_drawer)", "open(fridge)"]))
        for i, (action, available) in enumerate(steps):
            rows.append({"user": "ada", "time": f"2026-03-0{2 + day}T08:00:{10 * i:02d}", "duration": 5,
                         "action": action, "available": available})
    store = imported(rows, tmp_path, capsys)
    ask = ["rank", "--store", str(store), "--available", "open(small_drawer)", "open(fridge)",
           "--at", "2026-03-07T08:00:00", "--no-write", "--json"]
    assert main(ask) == 0
    # what was offered after the drawer lately, and no step after the one that ended each morning
    assert json.loads(capsys.readouterr().out)["chain"] == ["open(small_drawer)", "pick(banana)", "close(small_drawer)"]
    assert main([*ask, "--method", "thesis"]) == 0  # the thesis oracle's forward tree counts every morning alike
    assert json.loads(capsys.readouterr().out)["chain"] == ["open(small_drawer)", "pick(red_mug)", "close(small_drawer)"]


def test_rank_method_thesis_writes_the_thesis_ranking_and_names_the_method(store, capsys):
    capsys.readouterr()
    assert main(["rank", "--store", str(store), "--json", "--no-write", "--method", "thesis"]) == 0
    thesis = json.loads(capsys.readouterr().out)
    assert thesis["method"] == "thesis" and "probability" not in thesis["ranking"][0]
    assert main(["rank", "--store", str(store), "--json", "--no-write"]) == 0
    routine = json.loads(capsys.readouterr().out)
    assert routine["method"] == "personal"  # the default: the routine predictor's ranking until it learnt
    best = routine["ranking"][0]
    # the chain repeats exactly: its last three actions were followed by the next one twice
    assert best["call"] == "place(thermos, counter_top)" and best["context_order"] == 3 and best["similar"] == 2
    assert [r["score"] for r in routine["ranking"]] == sorted(r["score"] for r in routine["ranking"])
    assert main(["rank", "--store", str(store), "--method", "bayes"]) == 1
    assert ("unknown method 'bayes' (known: routine, routine-fixed, routine-mixture, stacked, online, pooled, personal, thesis, "
            "thesis-normalized)") in capsys.readouterr().err


def test_a_decision_after_a_pause_is_ranked_after_an_idle_step(store, capsys):
    """The next morning the pause since the last action is an idle gap: the history the ranking
    uses ends with that idle step (as the replay ranks it), so the chain's opening action leads,
    and "what was the context" says idle."""
    capsys.readouterr()
    assert main(["rank", "--store", str(store), "--available", "pick(red_mug)", "open(small_drawer)", "pick(banana)",
                 "--at", "2026-03-05T08:00:00", "--no-write", "--json"]) == 0
    later = json.loads(capsys.readouterr().out)
    assert later["history"] == 3 * len(CHAIN) + 3  # 2 nights logged as idle actions, and this pause
    best = later["ranking"][0]
    assert best["call"] == "open(small_drawer)" and best["context"][-1] == "idle"
    # a moment after the last action there is no pause: no idle step
    assert main(["rank", "--store", str(store), "--available", "pick(red_mug)", "open(small_drawer)",
                 "--at", "2026-03-04T08:01:00", "--no-write", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["history"] == 3 * len(CHAIN) + 2


def test_rank_keeps_its_fit_and_answers_the_same_with_it(store, tmp_path, monkeypatch, capsys):
    """The import kept the NEEM's fit in the store (oracle.fitcache): ranks find it and give the
    same ranking as a fit made afresh; a rank at an earlier moment (a shorter history) fits
    afresh, kept in the user's cache where the store is read-only (``--no-write``)."""
    from oracle.fitcache import KIND

    argv = ["rank", "--store", str(store), "--no-write", "--json"]
    capsys.readouterr()
    outs = []
    for cache in ("kept", "kept", "afresh"):
        if cache == "afresh":
            with open_store(store) as writer:  # nothing kept in the store: fitted afresh
                writer.write_kept(writer.neems()[0].id, KIND, b"")
        monkeypatch.setenv("NEEM_ORACLE_CACHE", str(tmp_path / cache))
        assert main(argv) == 0
        out = json.loads(capsys.readouterr().out)
        out.pop("ms")
        outs.append(out)
    assert outs[0] == outs[1] == outs[2]
    assert not (tmp_path / "kept" / "fits").exists()  # the store's fit served both
    monkeypatch.setenv("NEEM_ORACLE_CACHE", str(tmp_path / "cache"))
    early = ["rank", "--store", str(store), "--available", "pick(red_mug)", "open(small_drawer)",
             "--at", "2026-03-03T08:00:20", "--no-write", "--json"]
    assert main(early) == 0
    first = json.loads(capsys.readouterr().out)
    entry, = (tmp_path / "cache" / "fits").glob("*.fit")
    assert entry.stat().st_mode & 0o777 == 0o600
    written = entry.stat().st_mtime_ns
    assert main(early) == 0 and entry.stat().st_mtime_ns == written  # nothing new: nothing written
    capsys.readouterr()
    entry.unlink()
    assert main(early) == 0
    fresh = json.loads(capsys.readouterr().out)
    assert first["ranking"] == fresh["ranking"] and first["history"] == fresh["history"] < outs[0]["history"]


def test_the_terminal_names_the_objects_in_hand_only_where_no_context_backs_a_task():
    from oracle.algorithm.records import Option
    from oracle.algorithm.records import RoutineTask
    from oracle.commands.shown import describe

    mug = "https://ontology.dlr.de/soma/odb#RedMug"
    never = RoutineTask(1, 3.0, Option("https://ontology.dlr.de/soma/odb#Pick", mug), 0, 1.0, (), 0.125, -1, (), (),
                        (mug,))
    assert describe(never) == "    12% (no past context: by similarity; uses RedMug in hand)"
    followed = RoutineTask(1, 1.0, never.option, 4, 0.0, (), 0.5, 1, ("pick(RedMug)",), (3,), (mug,))
    assert describe(followed) == "    50% (followed [pick(RedMug)] 4x)"


def test_rank_says_who_usually_does_each_task_and_each_step(tmp_path, capsys):
    """The user pours, picks the thermos together with the robot, and the robot does the rest
    (``performed_by`` of the chains): rank's JSON
    carries each task's usual mode with its support and a mode per step of the chain, and the
    text says it in the tablet's words."""
    available = sorted(set(CHAIN + ["pick(banana)"]))
    rows = [{"user": "ada", "time": f"2026-03-0{2 + day}T08:00:{8 * i:02d}", "duration": 5, "action": action,
             "available": available, **({"performed_by": "user"} if action.startswith("pour") else
                                        {"performed_by": "together"} if action == "pick(thermos)" else {})}
            for day in range(3) for i, action in enumerate(CHAIN)]
    path = imported(rows, tmp_path, capsys)
    assert main(["rank", "--store", str(path), "--json", "--no-write", "--at", "2026-03-05T08:00:00"]) == 0
    out = json.loads(capsys.readouterr().out)
    by_call = {r["call"]: r for r in out["ranking"]}
    assert by_call["pour(thermos, red_mug)"]["mode"] == "user"
    assert by_call["pour(thermos, red_mug)"]["mode_support"] == {"context": "call and part",
                                                                 "counts": {"robot": 0, "user": 3, "together": 0}}
    assert by_call["pick(red_mug)"]["mode"] == "robot"
    assert by_call["pick(thermos)"]["mode"] == "together"  # the chains' third mode, imported and read back
    assert out["chain_modes"] == ["user" if step.startswith("pour") else "together" if step == "pick(thermos)" else "robot"
                                  for step in out["chain"]]
    assert main(["rank", "--store", str(path), "--no-write", "--at", "2026-03-05T08:00:00"]) == 0
    text = capsys.readouterr().out
    pour = next(line for line in text.splitlines() if line.split()[1:3] == ["pour(thermos,", "red_mug)"])
    assert pour.endswith("You usually do this yourself (3 of 3 times).")
