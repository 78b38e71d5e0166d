"""Plain words for the tablet: every call of the sample kitchen said in English and German, the
ontology's language-tagged labels first, a generated fallback, and the page's language."""

from __future__ import annotations

import re
from datetime import timezone

import pytest

from oracle.paths import data_dir
from oracle.service.words import LANGS, TEXT, Words, load_lexicon, pick_lang


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
