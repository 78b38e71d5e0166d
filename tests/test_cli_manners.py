"""The researcher's first contact with the command line (issue 58, findings 8-11), one test per
finding: each failed on the main branch before the issue's work."""

from __future__ import annotations

import io
import json
import os
import re
import shlex
import shutil
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from oracle.cli import main

pytestmark = pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed")


def run(argv: list[str]) -> int:
    """main's status, a usage error's (argparse exits) included."""
    try:
        return main(argv)
    except SystemExit as done:
        return int(done.code or 0)


@pytest.fixture(scope="module")
def demo(tmp_path_factory) -> tuple[Path, str]:
    """A store holding the demo NEEM, and what the demo printed."""
    path = tmp_path_factory.mktemp("manners") / "demo.sqlite"
    out = io.StringIO()
    real, sys.stdout = sys.stdout, out
    try:
        assert main(["demo", "--store", str(path)]) == 0
    finally:
        sys.stdout = real
    return path, out.getvalue()


def test_8_a_repeated_list_option_adds_up_and_a_repeated_value_is_refused(demo, capsys):
    store, _ = demo
    assert main(["rank", "--store", str(store), "--available", "open(fridge)", "--available", "pick(beer_bottle)",
                 "--at", "2025-03-08T08:05", "--dry-run", "--json"]) == 0
    ranked = json.loads(capsys.readouterr().out)["ranking"]
    assert sorted(r["call"] for r in ranked) == ["open(fridge)", "pick(beer_bottle)"]  # not only the last
    assert run(["rank", "--store", str(store), "--neem", "demo", "--neem", "other"]) == 2
    err = capsys.readouterr().err
    assert "--neem given twice ('demo' and 'other')" in err and len(err.strip().splitlines()) == 1


def test_9a_probabilities_are_percentages_and_no_score_is_left_unnamed(demo):
    _, printed = demo
    ranking = [line for line in printed.splitlines() if re.match(r"\s+\d\. ", line)]
    assert len(ranking) == 5
    assert all(re.search(r"\s(\d+%|\d\.\d+%|<0\.001%) \(", line) for line in ranking), ranking
    assert "p 0.000" not in printed and "score" not in printed  # round 3: "p 0.000", "(score 14.6)"


def test_9b_one_action_count_per_neem_and_the_breaks_named(demo, capsys):
    store, printed = demo
    said = re.search(r"NEEM 'demo' in .*: (\d+) actions .* \((\d+) tasks and (\d+) breaks, logged as idle actions\)", printed)
    assert said is not None, printed
    total, tasks, breaks = map(int, said.groups())
    assert total == tasks + breaks and breaks > 0
    assert main(["neems", "--store", str(store), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)[0]["actions"] == total  # round 3: 215 / 228 / 229
    ranked = re.search(r"NEEM \w+: (\d+) actions before the decision \((\d+) of them breaks", printed)
    assert ranked is not None and int(ranked.group(1)) == total and int(ranked.group(2)) == breaks


def test_9c_import_counts_as_neems_does(tmp_path, capsys):
    chains = tmp_path / "c.jsonl"
    rows = [{"user": "ada", "time": f"2026-03-0{2 + day}T08:00:{10 * i:02d}", "duration": 5, "action": action}
            for day in range(3) for i, action in enumerate(["open(fridge)", "pick(apple)", "close(fridge)"])]
    chains.write_text("".join(json.dumps(r) + "\n" for r in rows))
    assert main(["import", str(chains), "--store", str(tmp_path / "s.sqlite")]) == 0
    imported = re.search(r"\t(\d+) actions \(9 rows and (\d+) breaks?, logged as idle actions\)", capsys.readouterr().out)
    assert imported is not None
    assert main(["neems", "--store", str(tmp_path / "s.sqlite"), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)[0]["actions"] == int(imported.group(1)) == 9 + int(imported.group(2))


def test_10_ask_in_german_words_and_after_opening_answers_in_words(demo, capsys):
    store, _ = demo
    assert main(["ask", "--store", str(store), "wann habe ich zuletzt den Kühlschrank geöffnet?"]) == 0
    german = capsys.readouterr().out.strip()
    assert german.startswith("Zuletzt am ") and german.endswith(" den Kühlschrank geöffnet.")
    assert main(["ask", "--store", str(store), "what do I usually do after opening the fridge?"]) == 0
    english = capsys.readouterr().out
    assert english.startswith("After opening the fridge (done ") and "(" not in english.split("came", 1)[1]


def test_11a_import_shows_its_progress_and_honours_ctrl_c_in_every_phase(tmp_path, capsys, monkeypatch):
    """Every phase draws a bar with a total (rate and ETA on a terminal); a Ctrl-C during the
    fit that follows the logging exits 130 with one line (round 3: swallowed, exit 0)."""
    import contextlib

    import oracle.progress
    import oracle.ranking

    drawn: dict[str, list[tuple[int, int | None]]] = {}

    @contextlib.contextmanager
    def recording(label, unit="it", total=None, stream=None):
        ticks = drawn.setdefault(label.split()[0], [])
        yield lambda done, total_now=None: ticks.append((done, total_now))

    monkeypatch.setattr(oracle.progress, "bar", recording)
    chains = tmp_path / "c.jsonl"
    chains.write_text("".join(json.dumps({"user": "ada", "time": f"2026-03-02T08:{i:02d}:00", "duration": 5,
                                          "action": "open(fridge)" if i % 2 else "close(fridge)"}) + "\n" for i in range(40)))
    assert main(["import", str(chains), "--store", str(tmp_path / "a.sqlite")]) == 0
    assert drawn["checking"][-1] == (40, None) and drawn["logging"][-1] == (40, 40) and drawn["fitting"][-1] == (1, 1)

    def pressed(*args, **kwargs):
        os.kill(os.getpid(), signal.SIGINT)
        signal.sigtimedwait([], 0.05) if hasattr(signal, "sigtimedwait") else None
        raise AssertionError("the Ctrl-C was swallowed")

    monkeypatch.setattr(oracle.ranking, "keep_neem", pressed)
    capsys.readouterr()
    assert main(["import", str(chains), "--store", str(tmp_path / "b.sqlite")]) == 130
    err = capsys.readouterr().err.strip().splitlines()
    assert err == ["interrupted: every NEEM is imported; its first rank will read and fit it"]


def test_11a_a_bar_has_rate_and_eta_on_a_terminal_and_nothing_off_it():
    from oracle.progress import bar

    class Terminal(io.StringIO):
        def isatty(self) -> bool:
            return True

    screen, log = Terminal(), io.StringIO()
    for stream in (screen, log):
        with bar("logging", "actions", 100, stream=stream) as tick:
            for done in range(0, 101, 10):
                tick(done, 100)
    assert re.search(r"logging: 100%.*100/100 \[\d\d:\d\d<\d\d:\d\d, .* actions/s\]", screen.getvalue())
    assert log.getvalue() == ""


@pytest.mark.parametrize(("argv", "hint"), [
    (["rnak"], "no such command 'rnak'. Did you mean 'rank'?"),
    (["rank", "--avialable", "pick(apple)"], "Did you mean '--available'?"),
    (["why-not", "pik(banana)"], "unknown task 'pik'. Did you mean 'pick'?"),
    (["why-not", "pick(banan)"], "unknown object 'banan'. Did you mean 'banana'?"),
    (["why-not", "--neem", "dmeo", "pick(banana)"], "no NEEM 'dmeo' (neither an id nor a name; see 'neems'). Did you mean 'demo'?"),
])
def test_11b_did_you_mean(demo, capsys, argv, hint):
    store, _ = demo
    assert run([*argv[:1], "--store", str(store), *argv[1:]] if argv[0] != "rnak" else argv) in (1, 2)
    err = capsys.readouterr().err
    assert hint in err and len(err.strip().splitlines()) == 1


def test_11c_the_demos_closing_hint_runs_as_printed_outside_the_venv(demo):
    _, printed = demo
    hint = printed.strip().splitlines()[-1].split("try: ", 1)[1]
    words = shlex.split(hint)
    assert words[1:3] == ["-m", "oracle"] and Path(words[0]).exists()  # the interpreter, not a bare "python"
    env = {"PATH": "/usr/bin:/bin", "HOME": os.environ.get("HOME", "/root")}  # no venv on the PATH
    env.update({k: v for k, v in os.environ.items() if k.startswith(("NEEM_", "PYTHONPATH"))})
    done = subprocess.run([*words, "-q"], input="true.\n", capture_output=True, text=True, env=env, timeout=120)
    assert done.returncode == 0, done.stderr


def test_11d_prolog_json_is_refused_in_one_line(demo, capsys):
    store, _ = demo
    assert main(["prolog", "--store", str(store), "--json", "-g", "true"]) == 1
    err = capsys.readouterr().err
    assert err.startswith("error: prolog --json:") and len(err.strip().splitlines()) == 1


def test_11e_why_not_on_the_top_task_says_it_was_suggested(demo, capsys):
    store, _ = demo
    assert main(["rank", "--store", str(store), "--dry-run", "--json"]) == 0
    top = json.loads(capsys.readouterr().out)["ranking"][0]["call"]
    assert main(["why-not", "--store", str(store), top]) == 0
    said = capsys.readouterr().out
    assert f"I ranked {top} first" in said and "already done" not in said


def test_11f_an_exploratory_rank_writes_nothing(demo, capsys):
    store, _ = demo
    from oracle.store import open_store

    def preferences() -> int:
        with open_store(store, read_only=True) as opened:
            neem = opened.neems()[0].id
            return sum(1 for doc in opened.find(neem, p="http://www.w3.org/1999/02/22-rdf-syntax-ns#type")
                       if str(doc.get("o", "")).endswith("#PreferenceOrder"))

    before = preferences()
    assert main(["rank", "--store", str(store), "--available", "open(fridge)", "pick(apple)"]) == 0
    assert "not written: --available without --at" in capsys.readouterr().out
    assert main(["rank", "--store", str(store), "--dry-run"]) == 0
    assert preferences() == before


def test_11g_an_unreachable_mongo_is_one_short_line(capsys):
    assert main(["neems", "--store", "mongodb://127.0.0.1:1/nothing"]) == 1
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and len(err) < 160 and "Connection refused" in err, err
