"""Every question form answered on the hand-checked NEEM of conftest.py, in both languages."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from oracle.past.ask import ask
from oracle.past.forms import QuestionError, read_question
from tests.past.conftest import t

from oracle.timeline import seconds_of


def s(*args: int) -> float:
    return seconds_of(t(*args))


def test_when_did_i_last(bridge, onto):
    answer = ask(bridge, onto, "When did I last open the fridge?")
    assert answer.form == "last" and answer.language == "en"
    assert answer.evidence["task"] == "open(fridge)" and answer.evidence["begin"] == pytest.approx(s(1, 7, 5))
    assert answer.english == "Opening the fridge was last done at 07:05."
    assert answer.german == "Zuletzt um 07:05 den Kühlschrank geöffnet."
    before = ask(bridge, onto, "when did I last eat the apple", at=s(0, 11))
    assert before.evidence["begin"] is None and before.text == "Eating the apple was never done."


def test_how_often_today_and_this_week(bridge, onto):
    today = ask(bridge, onto, "how often did I open(fridge) today?")
    assert today.evidence["begins"] == [pytest.approx(s(1, 7, 5))]
    assert today.text == "Opening the fridge: 1 time today (at 07:05)."
    week = ask(bridge, onto, "Wie oft habe ich diese Woche open(fridge) gemacht?")
    assert week.language == "de" and len(week.evidence["begins"]) == 3
    assert week.text == ("Diese Woche 3-mal den Kühlschrank geöffnet (am 03.03.2025 um 07:00, am 03.03.2025 um 12:00, "
                         "um 07:05).")


def test_what_do_i_usually_do_after(bridge, onto):
    answer = ask(bridge, onto, "what do I usually do after open fridge?")  # open(fridge), not open_fridge
    assert answer.evidence["occurrences"] == 3
    assert answer.evidence["next"] == [{"task": "pick(milk_carton)", "count": 2}, {"task": "pick(apple)", "count": 1}]
    assert answer.text == ("After opening the fridge (done 3 times) came picking up the milk carton 2 times, picking up "
                           "the apple 1 time.")


def test_what_did_you_do_this_morning(bridge, onto):
    answer = ask(bridge, onto, "What did you do this morning?")
    tasks = [a["task"] for a in answer.evidence["actions"]]
    assert tasks == [*["open(fridge)", "pick(milk_carton)", "pour(milk_carton, cereal_bowl)"],
                     "pick(green_mug)", "place(green_mug, kitchen_table)"]
    assert answer.evidence["from"] == s(1, 5) and answer.evidence["to"] == pytest.approx(s(1, 8, 1, 30))
    german = ask(bridge, onto, "Was hast du heute mittag gemacht?", at=s(0, 13))
    assert [a["task"] for a in german.evidence["actions"]] == ["open(fridge)", "pick(apple)", "eat(apple)"]
    assert german.text.startswith("Heute mittag (11:00-13:00), 3 Handlungen: den Kühlschrank öffnen um 12:00")


def test_where_is(bridge, onto):
    answer = ask(bridge, onto, "where is the green mug?")
    assert answer.evidence["pose"]["position"] == [0.4, 1.2, 0.9]
    assert answer.evidence["used"]["task"] == "place(green_mug, kitchen_table)"
    assert answer.text == ("The green mug was last seen at (0.40, 1.20, 0.90) in map at 08:00. "
                           "The green mug was last used at 08:01 (putting the green mug on the table).")
    assert ask(bridge, onto, "wo ist die Müslischale").german == \
        "Zuletzt benutzt um 07:05: die Milch in die Müslischale gegossen."
    assert ask(bridge, onto, "where is the banana").text == "I have no record of where the banana is."


def test_why_did_you_suggest(bridge, onto):
    answer = ask(bridge, onto, "why did you suggest open(fridge)?")
    e = answer.evidence
    assert (e["rank"], e["score"], e["top"]) == (2, 0.5, "pick(green_mug)")
    # the action before 08:01 was Tuesday's pour; of the two pours, Monday's was followed by open(fridge)
    assert e["before"] == {"task": "pour(milk_carton, cereal_bowl)", "time": pytest.approx(s(1, 7, 5, 30)),
                           "occurrences": 2, "followed": 1}
    assert answer.english == ("At 08:01 I ranked opening the fridge 2nd; first was picking up the green mug. The action "
                              "before was pouring the milk into the cereal bowl, after which opening the fridge came 1 of 2 "
                              "times.")
    assert ask(bridge, onto, "warum hast du pick(apple) vorgeschlagen?").text == \
        "Ich habe nie vorgeschlagen: den Apfel nehmen."


def test_who_usually_does(bridge, onto):
    answer = ask(bridge, onto, "who usually does eat the apple?")
    assert answer.evidence["counts"] == {"user": 1, "robot": 0, "together": 0, "unknown": 0}
    assert answer.text == "You usually eat the apple yourself (1 of 1 time)."
    german = ask(bridge, onto, "Wer macht meistens open(fridge)?")
    assert german.text == "\u201eDen Kühlschrank öffnen\u201c macht meistens der Roboter für dich (3 von 3 Malen)."


@pytest.mark.parametrize("text", ["what's up?", "", "when did I last fly(plane)", "where is the unicorn",
                                  "when did I last pick the unicorn"])
def test_bad_questions_are_one_line_errors(onto, text):
    with pytest.raises(QuestionError) as error:
        read_question(text, onto)
    assert "\n" not in str(error.value)


def test_unknown_form_lists_the_forms(onto):
    with pytest.raises(QuestionError, match="when did I last open the fridge.*wann habe ich zuletzt"):
        read_question("tell me a joke", onto)


def test_cli_ask_json_and_error(small_store):
    run = [sys.executable, "-m", "oracle", "ask", "--store", str(small_store), "--neem", "small"]
    done = subprocess.run([*run, "when did I last pick(green_mug)?", "--json"], capture_output=True, text=True, check=True)
    reply = json.loads(done.stdout)
    assert reply["form"] == "last" and reply["text"] == "Picking up the green mug was last done at 08:01."
    bad = subprocess.run([*run, "sing a song"], capture_output=True, text=True)
    assert bad.returncode == 1 and bad.stderr.count("\n") == 1 and "not a question I know" in bad.stderr


def test_state_summary(bridge):
    from oracle.past.summary import state_summary

    summary = state_summary(bridge)
    assert summary["part_of_day"] == "Morning" and summary["today"] == 5
    assert summary["latest"]["task"] == "place(green_mug, kitchen_table)"
    assert [r["task"] for r in summary["recent"]][:3] == ["open(fridge)", "pick(milk_carton)", "pour(milk_carton, cereal_bowl)"]
    assert summary["usual_next"] == []  # the latest action was never followed yet
    assert [p["task"] for p in summary["predicted"]] == ["pick(green_mug)", "open(fridge)"]
