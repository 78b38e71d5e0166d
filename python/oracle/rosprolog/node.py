"""The ROS 1 node of the rosprolog door, run by Debian's ``/usr/bin/python3`` (where rospy is).

It imports nothing of this package: it generates the json_prolog_msgs service classes from the
.srv files beside it (genpy, into the user's cache, once per version of the files), registers
``/<ns>/query``, ``/<ns>/next_solution`` and ``/<ns>/finish`` (and ``/<ns>/simple_query``,
json_prolog's older name of query) with the master at
``ROS_MASTER_URI``, and forwards every call as one JSON line on stdout to the process that
started it, which answers on stdin (``ros.py``). The pipes are private to the two processes: no
port, no token. When stdin closes (that process ended) the node leaves the master.

Usage: python3 node.py SRV_DIR CACHE_DIR NAMESPACE
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import signal
import sys
import tempfile
import threading
from pathlib import Path
from typing import Any

PACKAGE = "json_prolog_msgs"
#: Seconds a call waits for the door's answer (its Prolog's time limit is far below it).
ANSWER_S = 120.0


def _private_folder(path: Path) -> Path:
    """``path`` and its missing parents, each 0700 whatever the umask. This node runs under
    Debian's python3, where the package (and oracle.files.private_folder) is not importable."""
    missing = [folder for folder in [path, *path.parents] if not folder.exists()]
    for folder in reversed(missing):
        folder.mkdir(mode=0o700)
        os.chmod(folder, 0o700)
    return path


def generated(srv_dir: Path, cache: Path) -> Path:
    """The folder holding the ``json_prolog_msgs`` package genpy makes of ``srv_dir``'s files."""
    from genpy.generate_initpy import write_modules
    from genpy.generator import SrvGenerator

    files = sorted(srv_dir.glob("*.srv"))
    digest = hashlib.sha256(b"".join(f.name.encode() + f.read_bytes() for f in files)).hexdigest()[:12]
    root = cache / f"{PACKAGE}-{digest}"
    if (root / PACKAGE / "srv" / "__init__.py").is_file():
        return root
    _private_folder(cache)  # each missing folder 0700 whatever the umask
    scratch = Path(tempfile.mkdtemp(dir=cache))  # 0700
    out = _private_folder(scratch / PACKAGE / "srv")
    if SrvGenerator().generate_messages(PACKAGE, [str(f) for f in files], str(out), {}):
        raise SystemExit("error: genpy could not generate the json_prolog_msgs service classes")
    write_modules(str(out))
    (scratch / PACKAGE / "__init__.py").write_text("")
    for made in scratch.rglob("*"):  # genpy writes with the umask's mode
        os.chmod(made, 0o700 if made.is_dir() else 0o600)
    try:
        os.rename(scratch, root)  # whole or not at all; another node may have made it meanwhile
    except OSError:
        shutil.rmtree(scratch, ignore_errors=True)
    return root


class Door:
    """The calls waiting for the door's answers, by number."""

    def __init__(self) -> None:
        self.lock = threading.Lock()
        self.count = 0
        self.waiting: dict[int, tuple[threading.Event, list[Any]]] = {}
        self.closed = False

    def call(self, service: str, args: dict[str, Any]) -> dict[str, Any]:
        event = threading.Event()
        box: list[Any] = []
        with self.lock:
            if self.closed:
                raise RuntimeError("the rosprolog door has stopped")
            self.count += 1
            number = self.count
            self.waiting[number] = (event, box)
            sys.stdout.write(json.dumps({"n": number, "service": service, "args": args}) + "\n")
            sys.stdout.flush()
        if not event.wait(ANSWER_S) or not box:
            with self.lock:
                self.waiting.pop(number, None)
            raise RuntimeError("the rosprolog door did not answer")
        answer: dict[str, Any] = box[0]
        if "error" in answer:
            raise RuntimeError(str(answer["error"]))
        return dict(answer["values"])

    def read_answers(self) -> None:
        for line in sys.stdin:
            answer = json.loads(line)
            with self.lock:
                event, box = self.waiting.pop(int(answer["n"]), (None, []))
            if event is not None:
                box.append(answer)
                event.set()
        with self.lock:  # the door's process is gone: wake every caller
            self.closed = True
            for event, _ in self.waiting.values():
                event.set()


def main(argv: list[str]) -> int:
    srv_dir, cache, namespace = Path(argv[0]), Path(argv[1]), argv[2].strip("/")
    # Ctrl-C reaches the whole process group: the door stops this node by closing its stdin
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    root = generated(srv_dir, cache)
    sys.path.insert(0, str(root))
    import rosgraph
    import rospy
    from json_prolog_msgs import srv

    master = rosgraph.get_master_uri()
    if not rosgraph.is_master_online(master):
        print(f"error: no ROS master at {master} (ROS_MASTER_URI): start one with 'rosmaster --core' or roscore",
              file=sys.stderr)
        return 3
    door = Door()

    def serve(service: str, response: Any, fields: tuple[str, ...]) -> Any:
        def handle(req: Any) -> Any:
            try:
                values = door.call(service, {name: getattr(req, name) for name in fields})
            except RuntimeError as error:
                raise rospy.ServiceException(str(error)) from None
            return response(**values)
        return handle

    # named as rosprolog's node is (after its namespace): a second door of another namespace on
    # the same master does not replace this one
    rospy.init_node(namespace.replace("/", "_"), disable_signals=True)
    services = [
        rospy.Service(f"/{namespace}/query", srv.PrologQuery, serve("query", srv.PrologQueryResponse, ("id", "query", "mode"))),
        rospy.Service(f"/{namespace}/next_solution", srv.PrologNextSolution,
                      serve("next_solution", srv.PrologNextSolutionResponse, ("id",))),
        rospy.Service(f"/{namespace}/finish", srv.PrologFinish, serve("finish", srv.PrologFinishResponse, ("id",))),
        # json_prolog's older name of query, which CRAM's client calls (with --namespace json_prolog)
        rospy.Service(f"/{namespace}/simple_query", srv.PrologQuery,
                      serve("query", srv.PrologQueryResponse, ("id", "query", "mode"))),
    ]
    with door.lock:
        sys.stdout.write(json.dumps({"ready": master, "classes": str(root)}) + "\n")
        sys.stdout.flush()
    door.read_answers()  # until the door's process closes the pipe
    for service in services:
        service.shutdown("the rosprolog door stopped")
    rospy.signal_shutdown("the rosprolog door stopped")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
