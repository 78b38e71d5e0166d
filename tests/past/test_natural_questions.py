"""``ask`` in natural English and German (issue 58, finding 10): the 20 + 20 questions of
natural_questions.yaml, asked of the demo NEEM, are answered as the same questions in the call
syntax are, in words with no code names."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import pytest
import yaml

from oracle.bridge import Bridge
from oracle.cli import main
from oracle.ontology import build_ontology
from oracle.past.ask import ask
from oracle.past.forms import read_question
from oracle.store import open_store

pytestmark = pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed")

QUESTIONS = yaml.safe_load((Path(__file__).parent / "natural_questions.yaml").read_text(encoding="utf-8"))
PAIRS = [(lang, item["ask"], item["same"]) for lang in ("en", "de") for item in QUESTIONS[lang]]
CODE = re.compile(r"[a-z_]+\([a-z_, ]*\)")


def test_twenty_questions_in_each_language():
    assert len(QUESTIONS["en"]) == len(QUESTIONS["de"]) == 20
    assert len({item["ask"] for items in QUESTIONS.values() for item in items}) == 40


@pytest.fixture(scope="module")
def demo(tmp_path_factory):
    path = tmp_path_factory.mktemp("natural") / "demo.sqlite"
    assert main(["demo", "--store", str(path)]) == 0
    onto = build_ontology()
    store = open_store(path, create=False)
    bridge = Bridge(store, "demo", onto)
    yield bridge, onto
    bridge.close()
    store.close()


@pytest.mark.parametrize(("lang", "natural", "code"), PAIRS, ids=[p[1] for p in PAIRS])
def test_a_natural_question_is_answered_as_its_call_syntax(demo, lang, natural, code):
    bridge, onto = demo
    asked, same = ask(bridge, onto, natural), ask(bridge, onto, code)
    assert asked.language == lang and asked.form == same.form
    assert asked.evidence == same.evidence and asked.text == same.text
    assert not CODE.search(asked.text), asked.text  # "den Kühlschrank geöffnet", not open(fridge)
    found = {k: v for k, v in asked.evidence.items() if k in ("begin", "occurrences", "actions", "begins", "pose", "used",
                                                               "time", "counts")}
    assert any(v not in (None, [], 0) for v in found.values()), f"the demo NEEM answers {natural!r} with nothing"


@pytest.mark.parametrize("text", ["after opening the fridge", "after open(fridge)"])
def test_after_opening_the_fridge_reads_as_after_open_fridge(text):
    question = read_question(f"what do I usually do {text}?", build_ontology())
    assert question.form == "after" and str(question.call) == "open(fridge)"
