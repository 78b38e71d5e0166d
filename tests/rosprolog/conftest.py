"""A store with one NEEM, a ROS master on a free port, the rosprolog door and the live service.

The ROS side needs Debian's ROS 1 (python3-rospy, python3-rosmaster: make setup installs them);
where it is missing those tests skip saying so. The rosbridge side needs no ROS at all.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.service.test_server import free_port, start_server, stop_server

ROOT = Path(__file__).resolve().parents[2]
ROS_PYTHON = "/usr/bin/python3"
CLIENT = Path(__file__).with_name("ros_client.py")


def has_ros() -> bool:
    if shutil.which("rosmaster") is None or not Path(ROS_PYTHON).exists():
        return False
    return subprocess.run([ROS_PYTHON, "-c", "import rospy, genpy, rosgraph"], capture_output=True).returncode == 0


needs_swipl = pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed; run make setup")
NO_ROS = "ROS 1 (Debian's python3-rospy, python3-rosmaster) is not installed; run make setup as root"
needs_ros = pytest.mark.skipif(not has_ros(), reason=NO_ROS)


@pytest.fixture(scope="session")
def neem_store(tmp_path_factory) -> Path:
    """A SQLite store holding one NEEM, alice's (tests.prolog.conftest.log_episode)."""
    from oracle.ontology import build_ontology
    from oracle.store import open_store
    from tests.prolog.conftest import log_episode

    path = tmp_path_factory.mktemp("rosprolog") / "s.sqlite"
    store = open_store(path)
    log_episode(store, build_ontology())
    store.close()
    return path


@pytest.fixture(scope="session")
def ros_env(tmp_path_factory) -> Iterator[dict[str, str]]:
    """``rosmaster --core`` on a free port; the environment that points ROS clients at it."""
    if not has_ros():
        pytest.skip(NO_ROS)
    port = free_port()
    home = tmp_path_factory.mktemp("ros-home")
    env = {**os.environ, "ROS_MASTER_URI": f"http://127.0.0.1:{port}", "ROS_HOME": str(home), "ROS_IP": "127.0.0.1"}
    master = subprocess.Popen(["rosmaster", "--core", "-p", str(port)], env=env, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL)
    code = "import rosgraph,sys; sys.exit(0 if rosgraph.is_master_online() else 1)"
    deadline = time.monotonic() + 30
    while subprocess.run([ROS_PYTHON, "-c", code], env=env).returncode != 0:
        if master.poll() is not None or time.monotonic() > deadline:
            master.kill()
            pytest.fail("rosmaster --core did not start")
        time.sleep(0.3)
    yield env
    master.terminate()
    master.wait(10)


def start_door(store: Path, env: dict[str, str], *extra: str) -> tuple[subprocess.Popen[str], str]:
    """``oracle rosprolog`` once its services are registered, and the PYTHONPATH of its classes."""
    door = subprocess.Popen([sys.executable, "-m", "oracle", "rosprolog", "--store", str(store), *extra], cwd=ROOT,
                            env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    assert door.stdout is not None
    line = door.stdout.readline()
    if "PYTHONPATH=" not in line:
        door.kill()
        pytest.fail(f"the rosprolog door did not start: {line}{door.stdout.read()}")
    return door, line.split("PYTHONPATH=", 1)[1].split(";", 1)[0]


def stop_door(door: subprocess.Popen[str]) -> None:
    door.send_signal(2)  # Ctrl-C: the door closes its node and says "stopped"
    try:
        door.wait(20)
    except subprocess.TimeoutExpired:
        door.kill()
        door.wait()


@pytest.fixture(scope="session")
def door(neem_store, ros_env) -> Iterator[dict[str, str]]:
    """The read-only door over the store; the environment a ROS client of it needs."""
    process, classes = start_door(neem_store, ros_env)
    yield {**ros_env, "PYTHONPATH": classes}
    stop_door(process)


def ros_client(env: dict[str, str], plan: dict) -> dict:
    """Run tests/rosprolog/ros_client.py (rospy's ServiceProxy, under Debian's python3) on ``plan``."""
    done = subprocess.run([ROS_PYTHON, str(CLIENT)], input=json.dumps(plan), env=env, capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0, done.stderr
    return dict(json.loads(done.stdout.strip().splitlines()[-1]))


@pytest.fixture(scope="session")
def service(neem_store) -> Iterator[str]:
    """``oracle serve`` over the store (read-only Prolog), its websocket base address."""
    port = free_port()
    process = start_server(neem_store, port)
    yield f"ws://127.0.0.1:{port}"
    stop_server(process)
