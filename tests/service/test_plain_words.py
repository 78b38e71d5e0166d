"""Words a person would say (issue 58, finding 5): prepositions per role, the part of the day
before a clock in German, a name (never an id) in the header, reasons that do not contradict
the usual mode and that differ where their evidence differs."""

from __future__ import annotations

from datetime import timezone

import pytest

from oracle.words import Words, load_lexicon


@pytest.fixture(scope="module")
def lexicon():
    return load_lexicon()


def words(lexicon, lang: str) -> Words:
    return Words(lexicon, lang, timezone.utc)


@pytest.mark.parametrize(("call", "en", "de"), [
    ("place(beer_bottle, fridge)", "Put the beer bottle in the fridge", "Die Bierflasche in den Kühlschrank stellen"),
    ("place(fork, big_drawer)", "Put the fork in the big drawer", "Die Gabel in die große Schublade stellen"),
    ("place(plate, counter_top)", "Put the plate on the counter", "Den Teller auf die Arbeitsplatte stellen"),
])
def test_a_thing_is_put_in_a_container_and_on_a_surface(lexicon, call, en, de):
    assert words(lexicon, "en").said(call) == en
    assert words(lexicon, "de").said(call) == de


def test_the_german_part_of_the_day_reads_as_an_adverb_not_tomorrow(lexicon):
    german = words(lexicon, "de")
    assert [german.part_of_day(p) for p in ("Morning", "Midday", "Evening", "Night")] == \
        ["morgens", "mittags", "abends", "nachts"]


@pytest.mark.parametrize(("user", "shown"), [("p003-none-blue-yogurt", ""), ("6b1703c1bb5a244c6b90efd5", ""),
                                             ("ada", "Ada"), ("Jan Müller", "Jan Müller"), (None, "")])
def test_the_header_names_a_person_never_an_id(lexicon, user, shown):
    assert words(lexicon, "en").person(user) == shown


def test_a_name_kept_with_the_neem_wins(lexicon):
    assert words(lexicon, "de").person("p003-none", {"person": "Frau Weber"}) == "Frau Weber"


def test_counts_of_the_task_with_other_objects_are_not_said_to_be_of_this_one(lexicon):
    """A task never done gets the robot's usual mode from the task's other calls: "this kind of
    task", so "You have not done this yet" is not followed by "the robot does this (51 of 51)"."""
    english = words(lexicon, "en")
    reason = english.reason({"support": 0, "context_order": -1, "probability": 0.01})
    mode = english.mode("robot", {"robot": 51, "user": 0, "together": 0}, "task")
    assert reason.startswith("You have not done this yet")
    assert mode == "The robot usually does this kind of task for you (51 of 51 times)."
    assert english.mode("robot", {"robot": 5, "user": 0, "together": 0}, "call") == \
        "The robot usually does this for you (5 of 5 times)."
    assert "Solche Aufgaben" in words(lexicon, "de").mode("robot", {"robot": 51, "user": 0, "together": 0}, "task and part")


def test_reasons_differ_where_their_evidence_differs(lexicon):
    """A new user's nine tasks, none done yet, each as likely as the ranking says: nine reasons
    where the chances differ (round 3 said one sentence nine times); the same chance, the same words."""
    english = words(lexicon, "en")
    chances = [0.31, 0.22, 0.14, 0.09, 0.07, 0.05, 0.04, 0.03, 0.002]
    reasons = [english.reason({"support": 0, "context_order": -1, "probability": p}) for p in chances]
    assert len(set(reasons)) == 9
    assert reasons[0] == "You have not done this yet; it is like what you do, so I give it about 31 in 100."
    assert reasons[-1].endswith("less than 1 in 100.")
    assert english.reason({"support": 0, "context_order": -1, "probability": 0.31}) == reasons[0]
    after = [english.reason({"support": 3, "context_order": 2, "context": ["open(fridge)"], "situations": [t]})
             for t in (1741330800.0, 1741334400.0)]  # the same count, last done at 07:00 and at 08:00
    assert after == ["You did this 3 times after opening the fridge, last at 07:00.",
                     "You did this 3 times after opening the fridge, last at 08:00."]


def test_what_people_usually_do_is_said_where_a_prior_says_so(lexicon):
    """An entry carrying a shared prior's share (``people``) of a task the person never did here
    says so, in both languages; the person's own counts win over it."""
    entry = {"support": 0, "context_order": -1, "probability": 0.05, "people": 0.42}
    assert words(lexicon, "en").reason(entry) == "Other people often do this next: about 42 in 100."
    assert words(lexicon, "de").reason(entry) == "Andere Menschen machen das oft als Nächstes: etwa 42 von 100."
    own = {**entry, "support": 3, "context_order": 0, "done": True}
    assert words(lexicon, "en").reason(own) == "You did this 3 times, but not at this point."


def test_a_new_users_reasons_are_not_one_sentence_nine_times(client):
    """Round 3: a new user's page said the same reason for all nine tasks shown. With two actions
    logged, the tasks' chances differ, and so do their reasons."""
    from tests.service.conftest import at

    neem = client.post("/api/neems", json={"user": "newcomer"}).json()["id"]
    for i, call in enumerate(["open(fridge)", "pick(milk_carton)"]):
        assert client.post(f"/api/neems/{neem}/actions", json={"call": call, "begin": at(0, 10 * i)}).status_code == 200
    offered = ["close(fridge)", "pick(apple)", "pick(banana)", "pick(red_mug)", "pour(milk_carton, red_mug)",
               "place(milk_carton, fridge)", "open(small_drawer)", "turn_on(stove)", "pick(cereal_bowl)"]
    assert client.post(f"/api/neems/{neem}/situation", json={"available": offered, "at": at(0, 30)}).status_code == 200
    view = client.get(f"/api/neems/{neem}/tablet", params={"lang": "en"}).json()
    reasons = [task["reason"] for task in view["tasks"]]
    assert len(reasons) == 9 and len(set(reasons)) >= 3, reasons
    assert view["person"] == "Newcomer"
