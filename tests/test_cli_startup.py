"""The fixed cost of a CLI call: ``--help`` imports no heavy library, and the parser built for
one command parses exactly as the complete one does."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from oracle.cli import build_parser, main

HEAVY = ("numpy", "pyswip", "rdflib", "yaml", "owlready2", "bson", "sqlite3", "oracle.ontology", "oracle.store")


def _loaded_after(argv: list[str]) -> list[str]:
    script = (
        "import json, sys\n"
        "from oracle.cli import main\n"
        "try:\n"
        f"    main({argv!r})\n"
        "except SystemExit:\n"
        "    pass\n"
        f"print(json.dumps([m for m in {HEAVY!r} if m in sys.modules]), file=sys.stderr)\n"
    )
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True)
    return json.loads(done.stderr.strip().splitlines()[-1])


@pytest.mark.parametrize("argv", [["--help"], [], ["neems", "--help"], ["rank", "--help"], ["--version"]])
def test_help_imports_no_heavy_library(argv: list[str]) -> None:
    assert _loaded_after(argv) == []


@pytest.mark.parametrize(
    "argv",
    [
        ["neems", "--store", "x.db", "--json"],
        ["rank", "--neem", "n", "--available", "pick(red_mug)", "--no-write"],
        ["ontology", "distance", "thermos", "pick"],
        ["import", "c.jsonl", "--commit-every", "5", "--replace"],
        ["why-not", "pick(red_mug)", "--store", "s.db"],
    ],
)
def test_the_one_command_parser_parses_as_the_complete_one(argv: list[str]) -> None:
    lazy = build_parser(argv[0], complete=False).parse_args(argv)
    full = build_parser().parse_args(argv)
    assert vars(lazy) == vars(full)


def test_a_misspelt_command_is_refused_with_the_list_of_commands(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as stop:
        main(["nems"])
    assert stop.value.code == 2
    assert "'neems'" in capsys.readouterr().err


def test_reading_a_store_imports_no_graph_library() -> None:
    """``neems`` and the store need IRIs as strings, never rdflib's graphs or numpy."""
    script = (
        "import sys\n"
        "import oracle.neem.query, oracle.store.sqlite, oracle.commands.store\n"
        "print([m for m in ('rdflib', 'numpy', 'pyswip', 'yaml', 'oracle.ontology') if m in sys.modules])\n"
    )
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True)
    assert done.stdout.strip() == "[]"
