"""KnowRob's doors against ``/api/prolog``: a query's first solution over rosprolog (ROS 1,
rospy's ServiceProxy as rosprolog_client calls it: ``query`` then ``next_solution``) and over the
service's rosbridge route (a websocket, as roslibpy calls it), beside the same query on
``/api/prolog`` (limit 1) measured in the same run: the floor the target (within 2x) is read
against. Two queries: ``X = 1`` (the transport alone) and a model query over a logged NEEM.

Every client opens its connection as its library does: urllib and rospy a new one per call
(rospy also asks the master where the service is), the websocket one for all; the ROS door is
measured a second time with persistent proxies (one connection), which leaves the door's own cost. Rounds alternate
the three so each meets the same load. Needs ROS 1 (Debian's python3-rospy, python3-rosmaster)
for the ROS figures; without it they are left out, said once.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from oracle.benchmarks.security import call, free_port, start, stop

QUERIES = ("X = 1", "kb_call(executes_task(A, T))")
ROUNDS = 3
ROS_PYTHON = "/usr/bin/python3"
#: rospy's proxies as rosprolog_client makes them (a new connection and a master look-up per
#: call), and persistent ones (one connection): the door's own cost without rospy's set-up.
ROS_DOORS = ("rosprolog (ROS 1)", "ROS 1, persistent")
#: The ROS client (Debian's python3): per query, ``n`` first solutions timed, in seconds.
ROS_TIMER = r"""
import json, sys, time, rospy
from json_prolog_msgs.srv import PrologFinish, PrologNextSolution, PrologQuery
plan = json.loads(sys.argv[1])
rospy.init_node("rosprolog_bench", anonymous=True, disable_signals=True)
for name in ("query", "next_solution", "finish"):
    rospy.wait_for_service("/rosprolog/" + name, timeout=60)
out = {}
for persistent in (False, True):
    query = rospy.ServiceProxy("/rosprolog/query", PrologQuery, persistent=persistent)
    next_solution = rospy.ServiceProxy("/rosprolog/next_solution", PrologNextSolution, persistent=persistent)
    finish = rospy.ServiceProxy("/rosprolog/finish", PrologFinish, persistent=persistent)
    for text in plan["queries"]:
        times = []
        for i in range(plan["n"]):
            qid = "bench_%d_%d_%d" % (plan["round"], persistent, i)
            started = time.perf_counter()
            query(id=qid, query=text, mode=1)
            answer = next_solution(id=qid)
            times.append(time.perf_counter() - started)
            finish(id=qid)
            assert answer.status == 3, answer.solution
        out["%d %s" % (persistent, text)] = times
print(json.dumps(out))
"""


def _has_ros() -> bool:
    if not Path(ROS_PYTHON).exists():
        return False
    return subprocess.run([ROS_PYTHON, "-c", "import rospy, rosmaster"], capture_output=True).returncode == 0


def _api(url: str, text: str, n: int) -> list[float]:
    times = []
    for _ in range(n):
        started = time.perf_counter()
        status, answer, _ = call(url, "/api/prolog", {"query": text, "neem": "bench", "limit": 1})
        times.append(time.perf_counter() - started)
        if status != 200 or not answer.get("solutions"):
            raise RuntimeError(f"/api/prolog {text!r}: {status} {answer}")
    return times


def _rosbridge(port: int, text: str, n: int, round_: int) -> list[float]:
    from websockets.sync.client import connect

    times = []
    with connect(f"ws://127.0.0.1:{port}/rosbridge", open_timeout=30) as socket:
        def service(name: str, args: dict[str, Any]) -> dict[str, Any]:
            socket.send(json.dumps({"op": "call_service", "service": f"/rosprolog/{name}", "args": args}))
            return dict(json.loads(socket.recv(timeout=60))["values"])

        for i in range(n):
            qid = f"bridge_{round_}_{i}"
            started = time.perf_counter()
            service("query", {"id": qid, "query": text, "mode": 1})
            answer = service("next_solution", {"id": qid})
            times.append(time.perf_counter() - started)
            service("finish", {"id": qid})
            if answer["status"] != 3:
                raise RuntimeError(f"rosbridge {text!r}: {answer}")
    return times


def _median(values: list[float]) -> float:
    ordered = sorted(values)
    return ordered[len(ordered) // 2]


def _neem(url: str) -> None:
    from oracle.service.robot import persona_rows

    user, steps = persona_rows(0, 3, 3)
    call(url, "/api/neems", {"user": user, "neem": "bench"})
    for row in steps[:20]:
        call(url, "/api/neems/bench/actions", {"call": str(row.action), "begin": row.time.timestamp()})


def _ros_door(store: Path, env: dict[str, str]) -> tuple[subprocess.Popen[str], subprocess.Popen[str], dict[str, str]]:
    """rosmaster and the rosprolog door over ``store``; the environment of a client."""
    port = free_port()
    env = {**env, "ROS_MASTER_URI": f"http://127.0.0.1:{port}", "ROS_IP": "127.0.0.1"}
    master = subprocess.Popen(["rosmaster", "--core", "-p", str(port)], env=env, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL, text=True)
    online = "import rosgraph,sys; sys.exit(0 if rosgraph.is_master_online() else 1)"
    deadline = time.monotonic() + 30
    while subprocess.run([ROS_PYTHON, "-c", online], env=env).returncode != 0:
        if time.monotonic() > deadline:
            raise RuntimeError("rosmaster --core did not start")
        time.sleep(0.3)
    door = subprocess.Popen([sys.executable, "-m", "oracle", "rosprolog", "--store", str(store)], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    line = door.stdout.readline() if door.stdout else ""
    if "PYTHONPATH=" not in line:
        raise RuntimeError(f"the rosprolog door did not start: {line}")
    return master, door, {**env, "PYTHONPATH": line.split("PYTHONPATH=", 1)[1].split(";", 1)[0]}


def run(quick: bool = False) -> list[dict[str, Any]]:
    n = 10 if quick else 40
    ros = _has_ros()
    if not ros:
        print("  (no ROS 1 in /usr/bin/python3: the ROS door's figures are left out; make setup installs it)", flush=True)
    times: dict[tuple[str, str], list[float]] = {}
    with tempfile.TemporaryDirectory() as folder:
        store = Path(folder) / "s.sqlite"
        env = {**os.environ, "ROS_HOME": str(Path(folder) / "ros")}
        service = start(store)
        master = door = None
        try:
            url = f"http://127.0.0.1:{service.port}"
            _neem(url)
            if ros:
                master, door, ros_env = _ros_door(store, env)
            for round_ in range(ROUNDS):
                for text in QUERIES:
                    times.setdefault(("/api/prolog", text), []).extend(_api(url, text, n))
                    times.setdefault(("rosbridge", text), []).extend(_rosbridge(service.port, text, n, round_))
                if ros:
                    plan = json.dumps({"queries": list(QUERIES), "n": n, "round": round_})
                    done = subprocess.run([ROS_PYTHON, "-c", ROS_TIMER, plan], env=ros_env, capture_output=True, text=True,
                                          timeout=600, check=True)
                    for key, values in json.loads(done.stdout.strip().splitlines()[-1]).items():
                        persistent, text = key.split(" ", 1)
                        times.setdefault((ROS_DOORS[int(persistent)], text), []).extend(values)
        finally:
            for process in (door, master):
                if process is not None:
                    process.terminate()
                    process.wait(20)
            stop(service)
    rows: list[dict[str, Any]] = []
    for text in QUERIES:
        floor = _median(times[("/api/prolog", text)])
        for door_name in ("/api/prolog", "rosbridge", *ROS_DOORS):
            if (door_name, text) not in times:
                continue
            median = _median(times[(door_name, text)])
            print(f"  first solution of {text!r:34s} {door_name:19s} median {median * 1000:7.2f} ms"
                  f"  ({median / floor:.2f}x /api/prolog; {len(times[(door_name, text)])} calls)", flush=True)
            rows.append({"area": "rosprolog", "name": f"{door_name}: {text}", "median_ms": round(median * 1000, 3),
                         "ratio_to_api_prolog": round(median / floor, 3), "calls": len(times[(door_name, text)])})
    return rows
