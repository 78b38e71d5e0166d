"""The bridge's process-wide state: pyswip's Prolog is one per process, and so are the bridge
whose store its foreign predicates read, the values a question hands over, the lock every use
of pyswip holds, and the crossings counted."""

from __future__ import annotations

import threading
from typing import TYPE_CHECKING, Any

from oracle.errors import PrologError

if TYPE_CHECKING:
    from oracle.bridge.connection import Bridge

LOCK = threading.RLock()
#: ``bridge``: the one the foreign predicates read; ``active``: the one Prolog is pointed at;
#: ``loaded``: the modules are loaded; ``request``: the values py_request/1 hands over.
STATE: dict[str, Any] = {"bridge": None, "active": None, "loaded": False, "request": None}
#: Crossings between the two languages: ``query``, every question Python asks Prolog; the
#: others, every time Prolog called into Python, per foreign predicate (a py_match counted
#: once, however many chunks it hands over).
CROSSINGS = {"query": 0, "py_match": 0, "py_insert": 0, "py_retract": 0, "py_graph": 0, "py_request": 0,
             "py_scopes": 0, "py_annotations": 0, "py_annotate": 0, "py_tf": 0, "py_dump": 0}


def crossings() -> int:
    """Every crossing so far, both ways (``CROSSINGS``); the py_request a question reads its
    values with is part of the question, not counted again."""
    return sum(count for name, count in CROSSINGS.items() if name != "py_request")


def connected() -> Bridge:
    """The bridge whose store Prolog's foreign predicates read (PrologError when none is)."""
    bridge: Bridge | None = STATE["bridge"]
    if bridge is None:
        raise PrologError("no store is connected to Prolog")
    return bridge
