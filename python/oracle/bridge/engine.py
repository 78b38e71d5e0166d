"""SWI-Prolog in this process through pyswip: the project's Prolog modules loaded once (from
the user's cache of compiled modules where it can), an engine for the calling thread, and a
question asked, its error made one clean line."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from oracle.bridge import foreign
from oracle.bridge.state import CROSSINGS, STATE
from oracle.bridge.values import atom, quote_atom
from oracle.errors import PrologError
from oracle.paths import prolog_dir

#: The Prolog modules under ``paths.prolog_dir()``, in load order (KnowRob's layout: the store's facade
#: neem_store over store/, then lang/, model/; the odb extension in odb/); each is imported into ``user`` so a
#: typed query sees its exports (the facade's re-exports are the same predicates as their home's).
MODULES = ("neem_store", "store/neem", "store/python", "store/pattern", "store/scope", "store/memory", "store/write",
           "store/read", "store/graph", "store/annotations", "store/tf", "json_text", "lang/triple", "lang/scope",
           "lang/query", "lang/aggregate", "lang/holds", "lang/temporal", "lang/db",
           "model/rdfs", "model/event", "model/object", "model/situation", "model/action", "model/interval", "model/tf",
           "model/owl", "model/owl_description", "model/dul_object_types", "model/dul_description", "model/soma_types",
           "model/soma_object", "model/soma_workflow", "model/soma_shape", "model/qudt", "reasoning/plowl",
           "lang/subgraph", "lang/rules", "lang/mongolog", "lang/computable",
           "compat/neem_interface", "compat/urdf", "compat/library/db/mongo/client",
           "odb/names", "odb/calls", "odb/events", "odb/decisions", "odb/history", "answers", "batch_toplevel")

def ensure_loaded() -> None:
    """Register the foreign predicates and load the Prolog modules, once per process."""
    if STATE["loaded"]:
        return
    foreign.register()
    folder = prolog_dir()
    paths = [folder / f"{name}.pl" for name in MODULES]
    for path in paths:
        if not path.exists():
            raise PrologError(f"{path}: Prolog module missing")
    if not _load_compiled(folder, paths):
        for path in paths:
            STATE["request"] = [atom(str(path))]
            run("store_python:py_request(R), R = [F], use_module(user:F)")
    STATE["request"] = None
    STATE["loaded"] = True


def _load_compiled(folder: Path, paths: list[Path]) -> bool:
    """Load the modules from the user's cache of compiled modules (oracle.modulecache), compiling
    them into it first when the entry for their content is missing; False when the cache cannot
    be used (the caller loads the sources)."""
    from oracle import modulecache

    version = str(run("current_prolog_flag(version, V)")[0]["V"])
    try:
        compiled = modulecache.compiled_path(folder, version)
        # Loaded means every module's source file is known to Prolog afterwards.
        files = [atom(str(path.resolve())) for path in paths]
        if compiled.is_file():
            STATE["request"] = [atom(str(compiled)), files]
            try:
                if not run("store_python:py_request(R), R = [F, Fs], catch(load_files(user:F, []), _, fail),"
                            " forall(member(S, Fs), source_file(S))"):
                    raise PrologError(f"{compiled}: does not load")
            except PrologError:
                modulecache.discard(compiled)  # damaged: the sources are loaded, and compiled next time
                raise
            modulecache.loaded(compiled)
            return True
        loader = modulecache.prepare(compiled, paths, quote_atom)
        # qcompile loads the modules, as use_module would, and writes the .qlf beside the loader.
        STATE["request"] = [atom(str(loader)), files]
        if not run("store_python:py_request(R), R = [F, Fs], qcompile(user:F, [include(user)]),"
                    " forall(member(S, Fs), source_file(S))"):
            modulecache.discard(loader)
            raise PrologError(f"{loader}: does not compile")
        modulecache.publish(loader, compiled)
        return True
    except (OSError, PrologError):
        return False  # the cache is an optimisation: a read-only or damaged one loads the sources


def attach_engine() -> None:
    """Give the calling thread a Prolog engine if it has none. Terms (atoms included) made on a
    thread without one crash the process, and pyswip attaches only inside ``Prolog.query``."""
    from pyswip.core import PL_thread_attach_engine, PL_thread_self

    if PL_thread_self() == -1 and PL_thread_attach_engine(None) == -1:
        raise PrologError("cannot attach a Prolog engine to this thread")


def run(query: str, maxresult: int = -1) -> list[dict[str, Any]]:
    """The solutions of one question (counted in CROSSINGS); a Prolog error as PrologError."""
    from pyswip import Prolog
    from pyswip.prolog import PrologError as PySwipError

    CROSSINGS["query"] += 1
    try:
        return list(Prolog.query(query, maxresult=maxresult))
    except PySwipError as error:
        raise PrologError(_clean_prolog_error(str(error))) from None


def _clean_prolog_error(text: str) -> str:
    if "neem_store_error" in text:
        start = text.find("neem_store_error(")
        return "store: " + text[start + len("neem_store_error("):].split(")", 1)[0].strip("'\"")
    return text.replace("Caused by: ", "").strip()
