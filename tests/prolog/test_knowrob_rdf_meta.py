"""KnowRob's model predicates take an IRI argument (mode ``r`` in their export lists, which KnowRob
declares rdf_meta) as ``prefix:'Local'`` or as the full IRI alike: each one asked both ways, on a
logged NEEM whose object has a shape and a colour, answers the same here (``object_shape/5``
threw ``type_error(atom, odb:...)``). The modes are read from KnowRob's source (tools/knowrob_api.py
finds it; skipped without one)."""

from __future__ import annotations

import importlib.util
import shutil
import sys
import tempfile
from pathlib import Path

import pytest

from oracle.errors import PrologError

pytestmark = pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed")

TOOL = Path(__file__).resolve().parents[2] / "tools" / "knowrob_api.py"
MODEL_FILES = ("src/model/RDFS.pl", "src/model/OWL.pl", "src/model/DUL.pl", "src/model/SOMA.pl", "src/model/QUDT.pl")
#: Export lists as KnowRob writes them: `name(r,?,t)` gives the modes.
READ_MODES = r"""
main :- current_prolog_flag(argv, Files),
    forall(member(File, Files),
      ( setup_call_cleanup(open(File, read, S), read_term(S, T, []), close(S)),
        T = (:- module(_, L)),
        forall(( member(I, L), compound(I), I \= _/_, I \= op(_,_,_) ),
               ( I =.. [N|Ms], atomic_list_concat(Ms, ',', Text), format("~w ~w~n", [N, Text]) )) )).
"""


def knowrob_modes() -> list[tuple[str, list[str]]] | None:
    spec = importlib.util.spec_from_file_location("knowrob_api", TOOL)
    assert spec and spec.loader
    tool = importlib.util.module_from_spec(spec)
    sys.modules["knowrob_api"] = tool
    spec.loader.exec_module(tool)
    texts = tool.knowrob_sources()
    if texts is None:
        return None
    with tempfile.TemporaryDirectory() as tmp:
        paths = []
        for i, f in enumerate(MODEL_FILES):
            (Path(tmp) / f"{i}.pl").write_text(texts[f], encoding="utf-8")
            paths.append(str(Path(tmp) / f"{i}.pl"))
        out = tool._swipl(READ_MODES, paths)
    return [(name, modes.split(",")) for name, modes in (line.split(" ", 1) for line in out.splitlines())]


def test_every_iri_argument_takes_a_prefixed_iri_as_the_full_one(tmp_path) -> None:
    modes = knowrob_modes()
    if modes is None:
        pytest.skip("no KnowRob source (KNOWROB_SRC or the git mirror at KNOWROB_GIT)")
    from oracle.bridge import Bridge
    from oracle.neem.writer import NeemLogger
    from oracle.ontology import build_ontology
    from oracle.store import open_store

    onto = build_ontology()
    store = open_store(tmp_path / "s.sqlite")
    log = NeemLogger.create(store, onto, user="u", neem_id="u")
    log.action("pick(apple)", 1.7e9, 1.7e9 + 3, action_id="a1")
    log.close()
    bridge = Bridge(store, log.neem_id, onto)
    ns = onto.namespace
    try:
        bridge.query("kb_project([holds(odb:'Object_apple', soma:hasShape, odb:'S1'), holds(odb:'S1', dul:hasRegion, odb:'R1'),"
                     " holds(odb:'R1', soma:hasRadius, 0.04), holds(odb:'Object_apple', soma:hasColor, odb:'C1'),"
                     " holds(odb:'C1', dul:hasRegion, odb:'CR1'), holds(odb:'CR1', soma:hasRGBValue, term([1,0,0]))])")

        def answers(goal: str) -> object:
            try:
                rows = bridge.query(f"catch(call_with_time_limit(5, findall(x, {goal}, L)), time_limit_exceeded, L = []),"
                                    " length(L, N)")  # fmt: skip
                return rows[0]["N"]
            except PrologError as error:
                return f"error: {str(error)[-200:]}"

        asked, differ = 0, []
        for name, arg_modes in modes:
            if "r" not in arg_modes or "t" in arg_modes:  # `t` arguments need a term of their own
                continue
            for local in ("Object_apple", "Action_a1"):
                prefixed = ", ".join(f"odb:'{local}'" if m == "r" else "_" for m in arg_modes)
                full = ", ".join(f"'{ns}{local}'" if m == "r" else "_" for m in arg_modes)
                asked += 1
                a, b = answers(f"{name}({prefixed})"), answers(f"{name}({full})")
                if a != b:
                    differ.append((name, local, a, b))
        assert asked > 250
        assert differ == []
        # and the shape answered at all (the object has one)
        assert answers("object_shape(odb:'Object_apple', _, sphere(0.04), _, material(rgba(1, 0, 0, _)))") == 1
    finally:
        bridge.close()
        store.close()
