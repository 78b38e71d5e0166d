"""``python -m oracle rosprolog``: KnowRob's rosprolog services over ROS 1, answered by this store."""

from __future__ import annotations

import argparse

from oracle.commands.common import NEEM, ONTOLOGY_OPTIONS, STORE, add_options
from oracle.errors import NeemOracleError

#: Default time limit of one page of a query, seconds (rosprolog has none; /api/prolog has 1 s
#: because it shares the robot's service: this door serves nothing else).
QUERY_SECONDS = 10.0


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    parser = subparsers.add_parser(
        "rosprolog", help="serve /rosprolog/query, next_solution and finish over ROS 1 (KnowRob's rosprolog_client)",
        description="Registers rosprolog's three services with the ROS master at ROS_MASTER_URI (start one with "
        "'rosmaster --core' or roscore) and answers them from one NEEM of the store, read-only unless "
        "--allow-prolog-writes. docs/knowrob.md.")
    add_options(parser, STORE, NEEM)
    parser.add_argument("--allow-prolog-writes", action="store_true",
                        help="let queries run kb_project/kb_unproject and neem-interface's logging (default: read-only)")
    parser.add_argument("--query-seconds", type=float, default=QUERY_SECONDS, metavar="S",
                        help=f"longest one query may run (default {QUERY_SECONDS:g})")
    parser.add_argument("--namespace", default="rosprolog", metavar="NS", help="the services' namespace (default rosprolog)")
    parser.add_argument("--ros-python", default=None, metavar="PATH",
                        help="the Python with rospy (default /usr/bin/python3, Debian's python3-rospy)")
    add_options(parser, *ONTOLOGY_OPTIONS)
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from oracle.files import default_cache_dir
    from oracle.rosprolog.backend import OwnBridge
    from oracle.rosprolog.protocol import Queries
    from oracle.rosprolog.ros import ROS_PYTHON, check_python, relay, start_node, stop_node

    if not 0 < args.query_seconds <= 600:
        raise NeemOracleError(f"--query-seconds {args.query_seconds}: expected more than 0 and at most 600")
    namespace = args.namespace.strip("/")
    if not namespace or not all(part.isidentifier() for part in namespace.split("/")):
        raise NeemOracleError(f"--namespace {args.namespace!r}: expected a ROS name such as rosprolog")
    python = args.ros_python or ROS_PYTHON
    check_python(python)  # before Prolog loads: a missing rospy is one line at once
    backend = OwnBridge(args, writes=args.allow_prolog_writes, seconds=args.query_seconds)
    node = None
    try:
        node, ready = start_node(namespace, default_cache_dir() / "rosprolog", python)
        mode = "writes allowed" if args.allow_prolog_writes else "read-only"
        print(f"rosprolog: /{namespace}/query, /{namespace}/next_solution, /{namespace}/finish at {ready.master} "
              f"answer NEEM {backend.neem} ({mode}); json_prolog_msgs for clients: PYTHONPATH={ready.classes}; "
              "Ctrl-C stops", flush=True)
        relay(node, Queries(backend.ask))
    except KeyboardInterrupt:
        pass
    finally:
        if node is not None:
            stop_node(node)
        backend.close()
    print("stopped", flush=True)
    return 0
