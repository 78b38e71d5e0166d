"""neem-oracle: KnowRob-compatible NEEM store, Prolog bridge and the oracle that ranks what an
assistive robot can do next.

The Python API (docs/python-api.md) is this package's top level: ``from oracle import
open_store, build_ontology, NeemLogger, Bridge, make_predictor, NeemRanker, rank_neem``. Each name
is imported from its module on first use (``__getattr__``), so ``import oracle`` (and every
``python -m oracle ... --help``) loads nothing heavy.
"""

from __future__ import annotations

from importlib import import_module
from typing import TYPE_CHECKING, Any

__version__ = "0.1.0"

#: Every name of the API and the module it lives in.
API: dict[str, str] = {
    # the store and the ontology
    "open_store": "oracle.store",
    "Store": "oracle.store",
    "build_ontology": "oracle.ontology",
    "OdbOntology": "oracle.ontology",
    # writing NEEMs
    "NeemLogger": "oracle.neem.writer",
    "import_chains": "oracle.neem.importing",
    # reading them through Prolog
    "Bridge": "oracle.bridge",
    "HistoryView": "oracle.bridge",
    "HistoryRow": "oracle.bridge",
    "LatestSituation": "oracle.bridge",
    # ranking
    "make_predictor": "oracle.ranking",
    "NeemRanker": "oracle.ranking",
    "NeemRanking": "oracle.ranking",
    "Decision": "oracle.ranking",
    "rank_neem": "oracle.ranking",
    "keep_neem": "oracle.ranking",
    "Hyperparameters": "oracle.algorithm.params",
    "Option": "oracle.algorithm.records",
    "Step": "oracle.algorithm.records",
    "Ranking": "oracle.algorithm.records",
    "RankedTask": "oracle.algorithm.records",
    "TaskCall": "oracle.chains",
    "parse_call": "oracle.chains",
    # time
    "Instant": "oracle.timeline",
    # errors
    "NeemOracleError": "oracle.errors",
    "OntologyError": "oracle.errors",
    "StoreError": "oracle.errors",
    "LoggingError": "oracle.errors",
    "PrologError": "oracle.errors",
}

__all__ = [
    "__version__",
    "open_store",
    "Store",
    "build_ontology",
    "OdbOntology",
    "NeemLogger",
    "import_chains",
    "Bridge",
    "HistoryView",
    "HistoryRow",
    "LatestSituation",
    "make_predictor",
    "NeemRanker",
    "NeemRanking",
    "Decision",
    "rank_neem",
    "keep_neem",
    "Hyperparameters",
    "Option",
    "Step",
    "Ranking",
    "RankedTask",
    "TaskCall",
    "parse_call",
    "Instant",
    "NeemOracleError",
    "OntologyError",
    "StoreError",
    "LoggingError",
    "PrologError",
]


def __getattr__(name: str) -> Any:
    module = API.get(name)
    if module is None:
        raise AttributeError(f"module 'oracle' has no attribute {name!r}")
    value = getattr(import_module(module), name)
    globals()[name] = value  # imported once
    return value


def __dir__() -> list[str]:
    return sorted(__all__)


if TYPE_CHECKING:
    from oracle.algorithm.params import Hyperparameters
    from oracle.algorithm.records import Option, RankedTask, Ranking, Step
    from oracle.bridge import Bridge, HistoryRow, HistoryView, LatestSituation
    from oracle.chains import TaskCall, parse_call
    from oracle.errors import LoggingError, NeemOracleError, OntologyError, PrologError, StoreError
    from oracle.neem.importing import import_chains
    from oracle.neem.writer import NeemLogger
    from oracle.ontology import OdbOntology, build_ontology
    from oracle.ranking import Decision, NeemRanker, NeemRanking, keep_neem, make_predictor, rank_neem
    from oracle.store import Store, open_store
    from oracle.timeline import Instant
