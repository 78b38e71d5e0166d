"""A rospy client of the rosprolog door (run by Debian's python3, not by pytest's Python).

Reads a plan on stdin: ``{"queries": [{"id", "query", "mode", "take", "finish"}], "parallel": N,
"parallel_query": TEXT, "namespace": NS}``; calls /rosprolog/query (or /NS/query), next_solution and finish through rospy's
ServiceProxy with the door's generated json_prolog_msgs classes; prints one JSON line: each
query's ``ok``, ``message`` and ``steps`` (``[status, solution]`` per next_solution, the last
one after ``finish`` when asked), and for ``parallel`` clients at once the number of errors.
"""

import json
import sys
import threading
import time

import rospy
from json_prolog_msgs.srv import PrologFinish, PrologNextSolution, PrologQuery

OK = 3


NAMESPACE = ["rosprolog"]


def proxies():
    ns = NAMESPACE[0]
    for name in ("query", "next_solution", "finish"):
        rospy.wait_for_service(f"/{ns}/{name}", timeout=60)
    return (rospy.ServiceProxy(f"/{ns}/query", PrologQuery),
            rospy.ServiceProxy(f"/{ns}/next_solution", PrologNextSolution),
            rospy.ServiceProxy(f"/{ns}/finish", PrologFinish))


def run(plan_item, query, next_solution, finish):
    opened = query(id=plan_item["id"], query=plan_item["query"], mode=plan_item.get("mode", 0))
    steps = []
    if opened.ok:
        take = plan_item.get("take", 10_000)
        while len(steps) < take:
            answer = next_solution(id=plan_item["id"])
            steps.append([answer.status, answer.solution])
            if answer.status != OK:
                break
        if plan_item.get("finish", True):
            finish(id=plan_item["id"])
            answer = next_solution(id=plan_item["id"])
            steps.append([answer.status, answer.solution])
    return {"ok": opened.ok, "message": opened.message, "steps": steps}


def crowd(count, text):
    """``count`` clients at once (each its own proxies, as separate processes would have), each
    its query to the end, half in each mode; the errors and the answers."""
    errors, answers = [], []

    def client(i):
        try:
            result = run({"id": f"crowd-{i}", "query": text, "mode": i % 2}, *proxies())
            answers.append(len([s for s in result["steps"] if s[0] == OK]))
        except Exception as error:  # counted, not raised: the test reads the count
            errors.append(repr(error))

    threads = [threading.Thread(target=client, args=(i,)) for i in range(count)]
    started = time.perf_counter()
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    return {"errors": errors, "answers": answers, "seconds": time.perf_counter() - started}


def main():
    plan = json.loads(sys.stdin.read())
    NAMESPACE[0] = plan.get("namespace", "rosprolog")
    rospy.init_node("rosprolog_test_client", anonymous=True, disable_signals=True)
    query, next_solution, finish = proxies()
    out = {"queries": [run(item, query, next_solution, finish) for item in plan.get("queries", [])]}
    if plan.get("parallel"):
        out["crowd"] = crowd(plan["parallel"], plan["parallel_query"])
    print(json.dumps(out))


if __name__ == "__main__":
    main()
