"""The checks a call to the NEEM writer (oracle.neem.writer) gets before anything is written: its
task and objects against the ontology, who performs it, the execution state reported."""

from __future__ import annotations

from oracle.chains import MODES, TaskCall, modes_error
from oracle.errors import LoggingError, OntologyError
from oracle.neem import terms as T
from oracle.ontology.model import OdbOntology


def check_state(state: object) -> None:
    """LoggingError unless ``state`` is None or an execution state KnowRob names."""
    if state is not None and state not in T.EXECUTION_STATES:
        raise LoggingError(f"state must be one of {', '.join(T.EXECUTION_STATES)}, got {state!r}")


#: Who may perform an action: the robot, the user it assists, or both together (chains.MODES).
PERFORMERS = MODES


def check_performer(who: object) -> str:
    """``who`` if it names a performer (PERFORMERS), else LoggingError."""
    if who not in PERFORMERS:
        raise LoggingError(modes_error(who))
    return str(who)


def check_call(onto: OdbOntology, call: TaskCall) -> None:
    """LoggingError unless the call's task and objects are in the ontology and its objects fit
    the task's roles (the checks an action gets before anything is written)."""
    if call.task not in onto.tasks:
        raise LoggingError(f"unknown task {call.task!r} in {call}; known tasks: {', '.join(sorted(onto.tasks))}")
    for arg in call.args:
        if arg not in onto.objects:
            raise LoggingError(f"unknown object {arg!r} in {call}")
    try:
        onto.task_roles(call.task, len(call.args))
    except OntologyError as error:
        raise LoggingError(str(error)) from None
