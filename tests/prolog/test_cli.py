"""The commands print one sentence (or JSON) and report user errors as one line, exit 1."""

from __future__ import annotations

import json
import subprocess
import sys

from oracle.cli import main
from oracle.store import open_store

from .conftest import log_episode


def _store(tmp_path, onto):
    path = tmp_path / "neems.sqlite"
    store = open_store(path)
    log_episode(store, onto)
    store.close()
    return str(path)


def test_why_not_json_and_sentence(tmp_path, onto, capsys):
    path = _store(tmp_path, onto)
    assert main(["why-not", "pick(apple)", "--at", "2024-05-01T08:02+00:00", "--store", path, "--json"]) == 0
    answer = json.loads(capsys.readouterr().out)
    assert answer["reasons"][0]["reason"] == "ranked_lower"
    assert main(["what-next", "--store", path]) == 0
    assert "Next I expect pick(apple)" in capsys.readouterr().out
    assert main(["something-else", "pour(thermos, green_mug)", "--store", path]) == 0
    assert "pick(apple)" in capsys.readouterr().out


def test_unknown_task_is_a_clear_error(tmp_path, onto, capsys):
    path = _store(tmp_path, onto)
    assert main(["why-not", "fly(banana)", "--store", path]) == 1
    assert "unknown task 'fly'" in capsys.readouterr().err
    assert main(["why-not", "pick(unicorn)", "--store", path]) == 1
    assert "unknown object 'unicorn'" in capsys.readouterr().err


def test_toplevel_with_piped_stdin(tmp_path, onto):
    path = _store(tmp_path, onto)
    queries = "aggregate_all(count, is_action(_), N).\nX = 'it''s'.\n"
    out = subprocess.run([sys.executable, "-m", "oracle", "prolog", "--store", path], input=queries,
                         capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    assert "N = " in out.stdout and "X = 'it\\'s'" in out.stdout


def _prolog(path, *args, stdin=""):
    return subprocess.run([sys.executable, "-m", "oracle", "prolog", "--store", path, *args], input=stdin,
                          capture_output=True, text=True, timeout=60)


def test_piped_queries_print_every_answer_and_errors_exit_non_zero(tmp_path, onto):
    path = _store(tmp_path, onto)
    out = _prolog(path, stdin="member(X, [a, b, c]).\nY = 1.\n")
    assert out.returncode == 0, out.stderr
    assert "X = a ;\nX = b ;\nX = c.\nY = 1.\n" in out.stdout and "Unknown action" not in out.stdout + out.stderr
    limited = _prolog(path, "--answers", "1", "-q", stdin="member(X, [a, b, c]).\n")
    assert limited.stdout == "X = a.\n" and limited.stderr == ""
    bad = _prolog(path, "-q", stdin="no_such_predicate(1).\nZ = 2.\n")
    assert bad.returncode == 1 and "no_such_predicate/1" in bad.stderr and "Z = 2." in bad.stdout


def test_prolog_g_runs_goals_like_swipl(tmp_path, onto):
    path = _store(tmp_path, onto)
    ok = _prolog(path, "-q", "-g", "aggregate_all(count, is_action(_), N), format('~w actions~n', [N])")
    assert ok.returncode == 0 and ok.stdout.strip().endswith("actions") and ok.stderr == ""
    assert _prolog(path, "-q", "-g", "fail").returncode == 1
    assert _prolog(path, "-q", "-g", "throw(oops)").returncode == 2


def test_answering_and_reading_the_history_load_no_json_or_rdf_parser(tmp_path, onto):
    # library(http/json), the RDF parsers and pcre cost tens of ms to load in every process:
    # the CLI's answers and history read must not need them (json_text writes their JSON).
    # A module loaded from a file, not one that exists at all: rdf_prefixes adds clauses to
    # rdf_db:ns/2 without loading library(semweb/rdf_db).
    path = _store(tmp_path, onto)
    goal = ("odb_history:situation_history_json(H), string_length(H, N), N > 0,"
            " findall(R, answers:why_not(pick(apple), R), Rs), Rs \\== [],"
            " forall(member(M, [json, rdf_db, turtle, pcre]), \\+ module_property(M, file(_))),"
            " format('clean~n')")
    out = _prolog(path, "-q", "-g", goal)
    assert out.returncode == 0 and out.stdout.strip() == "clean", out.stdout + out.stderr
    # and the check can fail: loading the library is seen
    loaded = _prolog(path, "-q", "-g", "use_module(library(semweb/rdf_db)), \\+ module_property(rdf_db, file(_))")
    assert loaded.returncode == 1
