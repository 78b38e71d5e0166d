"""pyswip: the one place Python and Prolog meet (this package is the only one that imports pyswip).

The Python process owns the store; SWI-Prolog runs the rules in prolog/. The package's parts:

``connection``
    ``Bridge``, Prolog connected to one NEEM, and the questions asked of it;
``engine``
    the Prolog modules loaded once per process, a thread's engine, a question asked;
``foreign``
    the foreign predicates Prolog calls in module ``store_python`` (the request channel),
    answering from the connected bridge's store;
``values``
    Python values as Prolog term text and pyswip terms, and back;
``records``
    what the oracle reads of a NEEM (history rows, the latest imagined situation);
``state``
    the process-wide state (pyswip's Prolog is one per process) and the crossings counted.

pyswip's traps (toolchain-facts §2) shape the code: outputs are always fresh variables
unified in Prolog, exceptions inside foreign predicates are caught and handed over as
``error(Message)`` (pyswip would turn them into silent failure), no ``Prolog.query`` runs
inside a foreign predicate, and every use of pyswip holds one process-wide lock.
"""

from __future__ import annotations

from oracle.bridge.connection import Bridge, connect
from oracle.bridge.engine import MODULES
from oracle.bridge.records import ROW_WIDTH, HistoryRow, HistoryView, LatestSituation, history_rows
from oracle.bridge.state import CROSSINGS, crossings
from oracle.bridge.values import QueryValueError, quote_atom, term_text

__all__ = ["Bridge", "CROSSINGS", "HistoryRow", "HistoryView", "LatestSituation", "MODULES", "QueryValueError", "ROW_WIDTH",
           "connect", "crossings", "history_rows", "quote_atom", "term_text"]
