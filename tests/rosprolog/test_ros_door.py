"""The ROS 1 door: rospy's own ServiceProxy (Debian's python3) against ``oracle rosprolog``."""

from __future__ import annotations

import json
import subprocess
import sys

from tests.rosprolog.conftest import ROOT, needs_ros, needs_swipl, ros_client, start_door, stop_door

pytestmark = [needs_swipl, needs_ros]
OK, NO_SOLUTION, WRONG_ID, QUERY_FAILED = 3, 0, 1, 2


def solutions(steps: list) -> list[dict]:
    return [json.loads(text) for status, text in steps if status == OK]


def test_all_solutions_once_incremental_failure_and_terms(door):
    result = ros_client(door, {"queries": [
        {"id": "all", "query": "member(X, [a, 1, 2.5, \"s\", [b]])", "mode": 0},
        {"id": "once", "query": "kb_call(executes_task(A, T))", "mode": 1, "take": 1},
        {"id": "inc", "query": "between(1, 13, X)", "mode": 1, "take": 5},
        {"id": "fail", "query": "no_such_predicate(X)", "mode": 1},
        {"id": "term", "query": "X = foo(a, [1, 2.5], \"str\"), Y = _", "mode": 0},
        {"id": "none", "query": "member(X, [])", "mode": 0},
    ]})
    everything, once, incremental, failing, term, none = result["queries"]
    assert all(q["ok"] for q in result["queries"])
    assert [s["X"] for s in solutions(everything["steps"])] == ["a", 1, 2.5, "\"s\"", ["b"]]
    assert everything["steps"][-2][0] == NO_SOLUTION  # then finish: the id is gone
    assert everything["steps"][-1][0] == WRONG_ID
    first = solutions(once["steps"])
    assert len(first) == 1 and first[0]["A"].startswith("http") and first[0]["T"].startswith("http")
    assert [s["X"] for s in solutions(incremental["steps"])] == [1, 2, 3, 4, 5]
    assert incremental["steps"][-1][0] == WRONG_ID  # finished after 5 of 13
    assert failing["steps"][0][0] == QUERY_FAILED and "no_such_predicate/1" in failing["steps"][0][1]
    assert solutions(term["steps"]) == [{"X": {"term": ["foo", "a", [1, 2.5], "\"str\""]}, "Y": "_"}]
    assert none["steps"][0] == [NO_SOLUTION, ""]


def test_ids_taken_finish_all_and_writes_refused(door):
    result = ros_client(door, {"queries": [
        {"id": "same", "query": "X = 1", "mode": 1, "take": 0, "finish": False},
        {"id": "same", "query": "X = 2", "mode": 1, "take": 0, "finish": False},
        {"id": "*", "query": "true", "mode": 0, "take": 0},  # finish("*") closes "same" too
        {"id": "same", "query": "X = 3", "mode": 0},
        {"id": "write", "query": "kb_project(triple(a, b, c))", "mode": 0},
    ]})
    first, taken, _, reopened, write = result["queries"]
    assert first["ok"] and not taken["ok"] and "already" in taken["message"]
    assert reopened["ok"] and solutions(reopened["steps"]) == [{"X": 3}]
    assert write["steps"][0][0] == QUERY_FAILED and "kb_project/1" in write["steps"][0][1]


def test_twenty_clients_at_once_without_errors(door):
    result = ros_client(door, {"parallel": 20, "parallel_query": "between(1, 13, X)"})
    assert result["crowd"]["errors"] == []
    assert result["crowd"]["answers"] == [13] * 20


def test_writes_where_allowed(neem_store, ros_env, tmp_path):
    import shutil

    store = tmp_path / "w.sqlite"
    shutil.copy(neem_store, store)
    # its own namespace on the same master: the read-only door beside it keeps serving
    process, classes = start_door(store, ros_env, "--allow-prolog-writes", "--namespace", "rosprolog_w")
    try:
        result = ros_client({**ros_env, "PYTHONPATH": classes}, {"namespace": "rosprolog_w", "queries": [
            {"id": "w", "query": "kb_project(triple(door_test_s, door_test_p, door_test_o))", "mode": 1, "take": 1},
            {"id": "r", "query": "kb_call(triple(door_test_s, door_test_p, O))", "mode": 0},
        ]})
    finally:
        stop_door(process)
    written, read = result["queries"]
    assert written["steps"][0][0] == OK, written
    assert solutions(read["steps"]) == [{"O": "door_test_o"}]


def test_no_master_is_one_line(neem_store, ros_env):
    env = {**ros_env, "ROS_MASTER_URI": "http://127.0.0.1:9"}
    done = subprocess.run([sys.executable, "-m", "oracle", "rosprolog", "--store", str(neem_store)], cwd=ROOT, env=env,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 1
    assert "error: the rosprolog node did not start" in done.stderr and "no ROS master at http://127.0.0.1:9" in done.stderr


def test_the_read_only_door_still_serves_after_another_came_and_went(door):
    """(runs after test_writes_where_allowed: a second door on the same master replaced nothing)"""
    result = ros_client(door, {"queries": [{"id": "again", "query": "X = 1", "mode": 1}]})
    assert solutions(result["queries"][0]["steps"]) == [{"X": 1}]


#: The MD5 sums of knowrob's json_prolog_msgs services (genmsg's, over the real .srv files):
#: a client built against the real package is served only when ours are the same.
JSON_PROLOG_MSGS_MD5 = {"PrologQuery": "b98fb21a498cfd5b16c55f4b1f1cfa7d",
                        "PrologNextSolution": "b101f472df7bcb78cc53cd5a17ecbda9",
                        "PrologFinish": "bbfcda76036ebbe3d36caf7af80b260c"}


def test_service_types_are_json_prolog_msgs_own(door):
    code = ("import json; from json_prolog_msgs import srv; "
            "print(json.dumps({n: getattr(srv, n)._md5sum for n in ('PrologQuery', 'PrologNextSolution', 'PrologFinish')}))")
    done = subprocess.run(["/usr/bin/python3", "-c", code], env=door, capture_output=True, text=True, timeout=60)
    assert json.loads(done.stdout) == JSON_PROLOG_MSGS_MD5, done.stderr
