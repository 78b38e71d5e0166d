"""The ROS 1 door: ``node.py`` under Debian's python3 registers the services, this process answers.

rospy is Debian's (python3-rospy), built for ``/usr/bin/python3``, not for this package's
interpreter; so the node runs there as a child with its stdin and stdout piped to this process.
It sends each call as a JSON line; ``relay`` answers each on a thread of its own (a slow query
holds no other client's call) through ``protocol.Queries``.
"""

from __future__ import annotations

import json
import subprocess
import sys
import threading
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path
from typing import IO, Any

from oracle.errors import NeemOracleError
from oracle.rosprolog.protocol import DoorError, Queries

#: The Python that has rospy (Debian's python3-rospy).
ROS_PYTHON = "/usr/bin/python3"
NODE = Path(__file__).with_name("node.py")
SRV_DIR = Path(__file__).with_name("srv")
#: Seconds the node may take to generate its classes and register with the master.
READY_S = 60.0
#: Calls answered at once (the rest wait their turn; Prolog answers one at a time anyway).
WORKERS = 8
MISSING = ("ROS 1's Python packages are missing from {python}: as root run "
           "apt-get install python3-rospy python3-rosmaster python3-genpy (make setup installs them)")


class RosDoorError(NeemOracleError):
    """The ROS 1 door cannot open (no rospy, no master, the node failed)."""


@dataclass(frozen=True)
class Ready:
    """What the node reports once its services are registered."""

    master: str
    #: The folder holding the generated json_prolog_msgs package (a client's PYTHONPATH).
    classes: str


def check_python(python: str = ROS_PYTHON) -> None:
    """RosDoorError unless ``python`` imports rospy and genpy."""
    try:
        done = subprocess.run([python, "-c", "import rospy, genpy, rosgraph"], capture_output=True, timeout=60)
    except (OSError, subprocess.TimeoutExpired):
        raise RosDoorError(MISSING.format(python=python)) from None
    if done.returncode != 0:
        raise RosDoorError(MISSING.format(python=python))


def start_node(namespace: str, cache: Path, python: str = ROS_PYTHON) -> tuple[subprocess.Popen[str], Ready]:
    """The node, running and registered (its stderr goes to ours: rospy's warnings stay visible)."""
    check_python(python)
    node = subprocess.Popen([python, str(NODE), str(SRV_DIR), str(cache), namespace], stdin=subprocess.PIPE,
                            stdout=subprocess.PIPE, text=True, bufsize=1)
    assert node.stdout is not None
    line = _first_line(node.stdout, READY_S)
    try:
        ready = json.loads(line) if line else {}
    except json.JSONDecodeError:
        ready = {}
    if "ready" not in ready:
        node.kill()
        node.wait()
        raise RosDoorError("the rosprolog node did not start (its message is above); is a ROS master running "
                           "at ROS_MASTER_URI? ('rosmaster --core' starts one)")
    return node, Ready(str(ready["ready"]), str(ready["classes"]))


def _first_line(stream: IO[str], seconds: float) -> str:
    box: list[str] = []
    reader = threading.Thread(target=lambda: box.append(stream.readline()), daemon=True)
    reader.start()
    reader.join(seconds)
    return box[0] if box else ""


def relay(node: subprocess.Popen[str], queries: Queries) -> None:
    """Answer the node's calls until it exits or its stdout closes."""
    assert node.stdin is not None and node.stdout is not None
    lock = threading.Lock()
    stdin = node.stdin

    def answer(call: dict[str, Any]) -> None:
        try:
            reply: dict[str, Any] = {"n": call["n"], "values": queries.call(str(call["service"]), dict(call["args"]))}
        except (DoorError, KeyError, TypeError, ValueError) as error:
            reply = {"n": call.get("n"), "error": str(error)}
        with lock:
            try:
                stdin.write(json.dumps(reply) + "\n")
                stdin.flush()
            except (BrokenPipeError, ValueError):
                pass  # the node is gone; its caller gets an error there

    with ThreadPoolExecutor(WORKERS, thread_name_prefix="rosprolog") as pool:
        for line in node.stdout:
            try:
                call = json.loads(line)
            except json.JSONDecodeError:
                print(f"rosprolog node: {line.rstrip()}", file=sys.stderr)
                continue
            pool.submit(answer, call)


def stop_node(node: subprocess.Popen[str]) -> None:
    """Close its stdin (it leaves the master on its own), then make sure it is gone."""
    if node.stdin is not None:
        try:
            node.stdin.close()
        except OSError:
            pass
    try:
        node.wait(10)
    except subprocess.TimeoutExpired:
        node.kill()
        node.wait()


__all__ = ["ROS_PYTHON", "Ready", "RosDoorError", "check_python", "relay", "start_node", "stop_node"]
