"""Runs code-iai/neem_interface_python's own read methods, unchanged, through the service's
rosbridge route (its package folder on sys.path; its ``utils/rosbridge.py`` connects to port 9090
of the host in ROS_MASTER_URI, as it does on a robot). The constructors are bypassed: they load
neem-interface.pl with ensure_loaded/1, which no service query may do (docs/knowrob.md). Prints
one JSON line of what each method returned."""

import json
import os
import sys
from concurrent.futures import ThreadPoolExecutor

from neem_interface_python.neem import NEEM
from neem_interface_python.neem_interface import NEEMError, NEEMInterface
from neem_interface_python.rosprolog_client import Prolog, PrologException

prolog = Prolog()
interface = NEEMInterface.__new__(NEEMInterface)
interface.prolog, interface.pool_executor = prolog, ThreadPoolExecutor(1)
neem = NEEM.__new__(NEEM)
neem.prolog, neem.neem_interface = prolog, interface
neem.episode = prolog.ensure_once("kb_call(is_episode(Episode))")["Episode"]
out = {"episode": neem.episode}
out["actions"] = sorted(interface.get_all_actions())
out["actions_typed"] = sorted(interface.get_all_actions("dul:'Action'"))
timed = prolog.ensure_all_solutions("is_action(Action), event_interval(Action, _, _)")
action = sorted(s["Action"] for s in timed)[0]
out["interval"] = list(interface.get_interval_for_event(action))
out["tasks"] = interface.get_tasks_for_action(action)
out["task_objects"] = interface.get_triple_objects(action, "dul:'executesTask'")
out["task_subjects"] = interface.get_triple_subjects("dul:'executesTask'", out["task_objects"][0])
out["top_level_action"] = neem.get_top_level_action()
try:
    out["participants"] = sorted(neem.get_participants())
except PrologException as error:  # its ensure_all_solutions when a query has no solution
    out["participants"] = str(error).splitlines()[0]
try:
    out["states"] = interface.get_all_states()
except (NEEMError, PrologException) as error:  # this NEEM logs no states: the method's own answer
    out["states"] = str(error).splitlines()[0]
print(json.dumps(out), flush=True)
sys.stdout.flush()
os._exit(0)  # its module-level roslibpy client keeps twisted's reactor running
