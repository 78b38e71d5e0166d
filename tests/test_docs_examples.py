"""The examples in docs/examples work as their README shows, and user docs hold no internal paths."""

from __future__ import annotations

import json
import re
import shutil
from pathlib import Path

import pytest

from oracle.cli import main

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "docs" / "examples"
ONTOLOGY = ["--odb", str(EXAMPLES / "odb"), "--mapping", str(EXAMPLES / "mapping.yaml")]


def test_the_examples_are_what_the_readme_says():
    assert sorted(p.parent.name for p in (EXAMPLES / "odb").glob("*/manifest.xml")) == ["_cup", "mug", "teapot"]
    assert len((EXAMPLES / "chains.jsonl").read_text().splitlines()) == 10


def test_ontology_build_from_the_examples(tmp_path, capsys):
    assert main(["ontology", "build", *ONTOLOGY, "--out", str(tmp_path / "tea.owl"), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["objects"] == 3 and summary["tasks"] == 4 and summary["tasks_with_default_mapping"] == ["drink_from"]


@pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed")
def test_import_rank_why_not_and_evaluate_the_examples(tmp_path, capsys):
    store = str(tmp_path / "tea.sqlite")
    settings = str(EXAMPLES / "settings.yaml")
    assert main(["import", str(EXAMPLES / "chains.jsonl"), *ONTOLOGY, "--store", store]) == 0
    # id, name, actions as neems counts them: the 10 rows and the break logged between them
    assert capsys.readouterr().out.split("\t", 1)[1] == "ada\t11 actions (10 rows and 1 break, logged as idle actions)\n"
    assert main(["rank", "--store", store, "--settings", settings, "--json", "--no-write",
                 "--available", "pick(teapot)", "pick(mug)", "drink_from(mug)", "--at", "2026-03-04T07:35:00"]) == 0
    ranking = json.loads(capsys.readouterr().out)
    assert ranking["history"] > 0 and len(ranking["ranking"]) == 3
    assert main(["why-not", "pick(mug)", "--store", store]) == 0
    assert capsys.readouterr().out.strip()
    assert main(["evaluate", str(EXAMPLES / "chains.jsonl"), *ONTOLOGY, "--settings", settings]) == 0
    assert "10 predictions" in capsys.readouterr().out


#: Paths of the machine the project was built on, and references to its issue tracker.
INTERNAL = re.compile(r"/work/|\.\./shared|\bissues? #?\d+|\(#\d+\)")


def test_user_docs_name_no_internal_paths_or_issue_numbers():
    pages = [ROOT / "README.md", ROOT / "docker" / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
    found = [f"{page.relative_to(ROOT)}:{n}: {line.strip()}" for page in pages
             for n, line in enumerate(page.read_text(encoding="utf-8").splitlines(), start=1) if INTERNAL.search(line)]
    assert not found, "\n".join(found)
