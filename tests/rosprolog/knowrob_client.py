"""Runs knowrob/rosprolog's own ``rosprolog_client.Prolog`` (the module folder on PYTHONPATH)
against the door, under Debian's python3; prints one JSON line of what each call returned."""

import json

import rospy
from rosprolog_client import Prolog, PrologException

rospy.init_node("rosprolog_client_test", anonymous=True, disable_signals=True)
prolog = Prolog(timeout=60)
out = {
    "all": prolog.all_solutions("member(X, [a, 1, 2.5, \"s\", [b]])"),
    "once": prolog.once("kb_call(executes_task(A, T))"),
    "none": prolog.once("member(X, [])"),
    "term": prolog.once("X = foo(a, [1, 2.5], \"str\"), Y = _"),
}
query = prolog.query("between(1, 13, X)")
out["incremental"] = [solution["X"] for solution in query.solutions()]
query = prolog.query("between(1, 13, X)")
taken = []
for solution in query.solutions():
    taken.append(solution["X"])
    if len(taken) == 3:
        break
query.finish()
out["finished_after_3"] = taken
try:
    prolog.once("no_such_predicate(X)")
    out["failure"] = None
except PrologException as error:
    out["failure"] = str(error)
print(json.dumps(out))
