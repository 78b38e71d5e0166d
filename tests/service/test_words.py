"""Plain words for the tablet: every call of the sample kitchen said in English and German, the
ontology's language-tagged labels first, a generated fallback, and the page's language."""

from __future__ import annotations

import re
from datetime import timezone

import pytest

from oracle.paths import data_dir
from oracle.words import LANGS, TEXT, Words, load_lexicon, pick_lang


@pytest.mark.parametrize("lang", LANGS)
def test_every_sample_call_is_said_without_call_syntax(lang):
    calls = set(re.findall(r'"([a-z_]+\([^)]*\))"', (data_dir() / "sample-chains.jsonl").read_text(encoding="utf-8")))
    words = Words(load_lexicon(), lang, timezone.utc)
    for call in sorted(calls):
        said = words.said(call)
        assert not re.search(r"[_()]", said) and said[0].isupper(), (call, said)
        assert not re.search(r"[_()]", words.said(call, "after")), call
    assert Words(load_lexicon(), "en", timezone.utc).said("pour(beer_bottle, drinking_glass)") == "Pour the beer into the glass"
    assert Words(load_lexicon(), "de", timezone.utc).said("drink_from(red_mug)") == "Aus dem roten Becher trinken"


def test_the_ontologys_tagged_label_wins_and_unknown_names_fall_back(onto):
    from rdflib import RDFS, Literal, URIRef

    fridge = URIRef(onto.objects["fridge"].iri)
    label = Literal("den Eisschrank", lang="de")
    onto.graph.add((fridge, RDFS.label, label))
    try:
        words = Words(load_lexicon(ontology=onto), "de", timezone.utc)
        assert words.said("open(fridge)") == "Den Eisschrank öffnen"
    finally:
        onto.graph.remove((fridge, RDFS.label, label))
    english = Words(load_lexicon(), "en", timezone.utc)
    assert english.said("turn_on(space_heater)") == "Turn on the space heater"  # no template: the names, spaced
    assert english.said("not a call") == "not a call"


def test_the_language_is_asked_else_the_browsers_else_english():
    assert pick_lang("de", "en-US") == "de"
    assert pick_lang(None, "fr-FR,de;q=0.8,en;q=0.5") == "de"
    assert pick_lang("xx", "fr") == "en"
    assert set(TEXT["en"]) == set(TEXT["de"])  # every sentence in both languages


@pytest.mark.parametrize("mode,counts,en,de", [
    ("user", {"robot": 1, "user": 5, "together": 0}, "You usually do this yourself (5 of 6 times).",
     "Das machen Sie meist selbst (5 von 6 Malen)."),
    ("robot", {"robot": 1, "user": 0, "together": 0}, "The robot usually does this for you (1 of 1 time).",
     "Das macht meist der Roboter für Sie (1 von 1 Mal)."),
    ("together", {"robot": 2, "user": 0, "together": 2}, "You usually do this together with the robot (2 of 4 times).",
     "Das machen Sie meist zusammen mit dem Roboter (2 von 4 Malen)."),
    # the predictor says other than these counts' most frequent: likely, not usual, and no figure
    ("user", {"robot": 4, "user": 3, "together": 0}, "You would likely do this yourself.",
     "Das würden Sie wohl selbst machen."),
    ("robot", {"robot": 0, "user": 2, "together": 0}, "The robot would likely do this for you.",
     "Das würde wohl der Roboter für Sie machen."),
    (None, {"robot": 0, "user": 0, "together": 0}, "", ""),
])
def test_who_usually_does_it_in_both_languages(mode, counts, en, de):
    assert Words(load_lexicon(), "en", timezone.utc).mode(mode, counts) == en
    assert Words(load_lexicon(), "de", timezone.utc).mode(mode, counts) == de
