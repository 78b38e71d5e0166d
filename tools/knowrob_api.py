"""KnowRob 2.x's non-ROS API against ours: which of the predicates KnowRob master exports exist here.

Reads the export lists of KnowRob's module files (``FILES``, 245 predicates) from a KnowRob checkout
(``$KNOWROB_SRC``: a folder holding ``src/``) or from the git mirror (``$KNOWROB_GIT``, default
``/work/.mirror/knowrob+knowrob/repo``, branch master), loads this project's Prolog modules in a
plain ``swipl`` and asks for each predicate whether it is defined. ``NOTES`` says how a present
predicate differs from KnowRob's and why an absent one is absent; the rest are supported.

    python tools/knowrob_api.py                # the table on stdout, counts on stderr
    python tools/knowrob_api.py --write        # docs/knowrob-api.md
    python tools/knowrob_api.py --check        # exit 1 when docs/knowrob-api.md is stale
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))
from oracle.bridge import MODULES  # noqa: E402

TABLE = ROOT / "docs" / "knowrob-api.md"
DEFAULT_GIT = Path("/work/.mirror/knowrob+knowrob/repo")

#: KnowRob master's non-ROS modules whose exports make up its public API: the query language
#: (lang, terms, mongolog's entry points), the models (RDFS, OWL, DUL, SOMA, QUDT, terms) and
#: the reasoners over them (plowl, temporal).
FILES = (
    "src/lang/query.pl", "src/lang/scope.pl", "src/lang/db.pl", "src/lang/computable.pl", "src/lang/subgraph.pl",
    "src/lang/terms/holds.pl", "src/lang/terms/temporal.pl", "src/lang/terms/triple.pl",
    "src/lang/mongolog/mongolog.pl", "src/lang/mongolog/database.pl", "src/lang/mongolog/fluents.pl",
    "src/model/RDFS.pl", "src/model/OWL.pl", "src/model/DUL.pl", "src/model/SOMA.pl", "src/model/QUDT.pl",
    "src/model/terms.pl", "src/reasoning/OWL/plowl/class.pl", "src/reasoning/OWL/plowl/individual.pl",
    "src/reasoning/OWL/plowl/property.pl", "src/reasoning/temporal/interval.pl", "src/reasoning/temporal/workflow.pl",
)  # fmt: skip

#: Modules of this project that only the tests and tools load (not the bridge).
EXTRA_MODULES: tuple[str, ...] = ()

_MONGO = "MongoDB-only machinery: the store is reached through store_match/3 on every backend"
_KR_DATA = "NEEM dumps enter and leave the store from Python (`python -m oracle load`, `export`)"

#: How a present predicate differs from KnowRob's (``differs``), or why one is absent (``absent``).
NOTES: dict[str, tuple[str, str]] = {
    "kb_call/1": ("differs", "compiled to one store query per run of triple goals on every backend (SQLite, MongoDB, memory)"),
    "universal_scope/1": ("differs", "gives `scope(0.0, inf)`, accepted wherever KnowRob's dictionaries go"),
    "current_scope/1": ("differs", "gives `scope(Now, Now)`, accepted wherever KnowRob's dictionaries go"),
    "load_owl/1": ("differs", "owl:imports are not followed (the graph hierarchy is); `package://` without ROS (docs/prolog.md)"),
    "load_owl/2": ("differs", "as load_owl/1"),
    "load_owl/3": ("differs", "as load_owl/1; the third argument is the graph"),
    "kb_unproject/1": ("differs", "deletes the matching documents; `o*` closures of other documents are not shrunk"),
    "is_resource/1": ("differs", "typed rdfs:Resource, rdfs:Class or owl:Class: a NEEM does not carry the RDF vocabulary's own axioms"),
    "is_property/1": ("differs", "typed rdf:Property or an OWL property class, for the same reason"),
    "kb_unproject/2": ("differs", "as kb_unproject/1: the matching documents go whatever their scopes"),
    "kb_unproject/3": ("differs", "as kb_unproject/2; options are accepted, not read"),
    "load_graph_structure/0": ("differs", "does nothing: the store's graphs are read into the hierarchy whenever a query names a graph"),
    "mongolog_call/1": ("differs", "kb_call/1: the compiler builds one store query on every backend, not only a MongoDB pipeline"),
    "mongolog_call/2": ("differs", "kb_call/2 with the scope of the `scope(S)` option"),
    "qudt_unit/4": ("differs", "the 13 units holds/3 reads and writes (length, mass, time, plane angle), not all of QUDT's unit.owl"),
    "qudt_conv/4": ("differs", "between those 13 units"),
    "has_object_type/2": ("differs", "an asserted type below dul:Object (KnowRob's has_type/2 reads the most specific type)"),
    "is_a/2": ("differs", "subclass_of/2 for a resource typed owl:Class or rdfs:Class, else instance_of/2 (KnowRob: is_individual/1)"),
    "computables/1": ("differs", "`property(P)` and KnowRob's misspelt `propery(P)` both name a computable property"),
    "owl_individual_of/3": ("differs", "FScope of `Q->F` is the question scope, not the facts' intersection"),
    "owl_has/4": ("differs", "as owl_individual_of/3 for the scope argument"),
    "owl_cardinality/5": ("differs", "as owl_individual_of/3 for the scope argument"),
    "action_pending/1": ("absent", "the execution states of actions come with the NEEM writer's (model/action.pl)"),
    "action_cancelled/1": ("absent", "as action_pending/1"),
    "mng_triple_doc/3": ("absent", _MONGO),
    "mongolog_add_predicate/3": ("absent", _MONGO + " (collections of n-ary predicates)"),
    "mongolog_drop_predicate/1": ("absent", _MONGO),
    "mongolog_add_fluent/3": ("absent", _MONGO + " (fluent collections)"),
    "mongolog_add_fluent/4": ("absent", _MONGO + " (fluent collections)"),
    "mongolog_drop_fluent/1": ("absent", _MONGO),
    "setup_collection/2": ("absent", "the stores create KnowRob's 15 indexes themselves"),
    "watch/3": ("absent", "MongoDB change streams; the service's event stream plays this part"),
    "watch_event/2": ("absent", "as watch/3"),
    "unwatch/1": ("absent", "as watch/3"),
    "load_json_rdf/1": ("absent", "JSON-RDF files are not read"),
    "remember/1": ("absent", _KR_DATA),
    "memorize/1": ("absent", _KR_DATA),
    "drop_graph/1": ("absent", _KR_DATA),
}  # fmt: skip


@dataclass(frozen=True)
class Export:
    """One predicate a KnowRob module exports, and how it stands here."""

    module: str
    name: str
    arity: int
    status: str
    note: str

    @property
    def key(self) -> str:
        return f"{self.name}/{self.arity}"


def knowrob_sources() -> dict[str, str] | None:
    """The text of every file of FILES, or None when no KnowRob source is found."""
    src = os.environ.get("KNOWROB_SRC")
    if src:
        folder = Path(src)
        if not all((folder / f).is_file() for f in FILES):
            return None
        return {f: (folder / f).read_text(encoding="utf-8") for f in FILES}
    git = Path(os.environ.get("KNOWROB_GIT", DEFAULT_GIT))
    if not git.is_dir():
        return None
    texts = {}
    for f in FILES:
        done = subprocess.run(["git", "-C", str(git), "show", f"master:{f}"], capture_output=True, text=True)
        if done.returncode != 0:
            return None
        texts[f] = done.stdout
    return texts


_READ_EXPORTS = r"""
item(F/A, F, A) :- !.
item(op(_,_,_), _, _) :- !, fail.
item(T, F, A) :- compound(T), !, functor(T, F, A).
item(T, T, 0) :- atom(T).
main :- current_prolog_flag(argv, Files),
    forall(member(File, Files),
      ( setup_call_cleanup(open(File, read, S), read_term(S, T, []), close(S)),
        T = (:- module(M, L)),
        forall(( member(I, L), item(I, F, A) ), format("~w ~q ~w~n", [M, F, A])) )).
"""

_PROBE = r"""
main :- current_prolog_flag(argv, [Modules|Keys]),
    split_string(Modules, ",", "", Ms),
    forall(member(M, Ms), use_module(user:M)),
    forall(member(K, Keys),
      ( split_string(K, "/", "", [N, A]), atom_string(Name, N), number_string(Ar, A),
        ( current_predicate(user:Name/Ar) -> S = present ; S = missing ),
        format("~w ~w~n", [K, S]) )).
"""


def _swipl(program: str, argv: list[str]) -> str:
    with tempfile.NamedTemporaryFile("w", suffix=".pl", delete=False) as f:
        f.write(program)
    try:
        done = subprocess.run(["swipl", "-q", "-g", "main", "-t", "halt", f.name, "--", *argv],
                              capture_output=True, text=True, timeout=300, cwd=ROOT)
    finally:
        os.unlink(f.name)
    if done.returncode != 0:
        raise SystemExit(f"swipl failed: {done.stderr.strip()[-2000:]}")
    return done.stdout


def knowrob_exports(texts: dict[str, str]) -> list[tuple[str, str, int]]:
    """(module, name, arity) of every export of the files, in file order."""
    with tempfile.TemporaryDirectory() as tmp:
        paths = []
        for i, f in enumerate(FILES):
            path = Path(tmp) / f"{i:02d}.pl"
            path.write_text(texts[f], encoding="utf-8")
            paths.append(str(path))
        out = _swipl(_READ_EXPORTS, paths)
    rows = []
    for line in out.splitlines():
        module, name, arity = line.rsplit(" ", 2)
        rows.append((module, name.strip("'"), int(arity)))
    return rows


def probe(exports: list[tuple[str, str, int]]) -> list[Export]:
    """Each export with its status here: supported, differs (present, NOTES says how) or absent."""
    modules = ",".join(str(ROOT / "prolog" / f"{m}.pl") for m in (*MODULES, *EXTRA_MODULES))
    keys = [f"{n}/{a}" for _, n, a in exports]
    found = dict(line.rsplit(" ", 1) for line in _swipl(_PROBE, [modules, *keys]).splitlines())
    rows = []
    for module, name, arity in exports:
        key = f"{name}/{arity}"
        kind, note = NOTES.get(key, ("", ""))
        if found[key] == "present":
            status = "differs" if kind == "differs" else "supported"
            note = note if kind == "differs" else ""
        else:
            status = "absent"
            note = note if kind == "absent" else "no reason recorded"
        rows.append(Export(module, name, arity, status, note))
    return rows


def render(rows: list[Export]) -> str:
    counts = {s: sum(r.status == s for r in rows) for s in ("supported", "differs", "absent")}
    lines = [
        "# KnowRob 2.x's non-ROS API here",
        "",
        "Generated by `python tools/knowrob_api.py --write` from the export lists of KnowRob master's",
        "modules (the files below) and the Prolog modules of this project; do not edit by hand.",
        "`tests/prolog/test_knowrob_api.py` checks it is up to date when the KnowRob source is present.",
        "",
        f"{len(rows)} predicates: {counts['supported']} supported, {counts['differs']} differ, "
        f"{counts['absent']} absent ({counts['supported'] + counts['differs']} present).",
        "",
        "| KnowRob module | predicate | here | how / why |",
        "| --- | --- | --- | --- |",
    ]
    lines += [f"| `{r.module}` | `{r.key}` | {r.status} | {r.note} |" for r in rows]
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--write", action="store_true", help=f"write {TABLE.relative_to(ROOT)}")
    group.add_argument("--check", action="store_true", help=f"exit 1 when {TABLE.relative_to(ROOT)} is stale")
    args = parser.parse_args(argv)
    texts = knowrob_sources()
    if texts is None:
        print("no KnowRob source: set KNOWROB_SRC (a checkout) or KNOWROB_GIT (a git mirror)", file=sys.stderr)
        return 2
    rows = probe(knowrob_exports(texts))
    table = render(rows)
    present = sum(r.status != "absent" for r in rows)
    print(f"{present} of {len(rows)} present", file=sys.stderr)
    if args.write:
        TABLE.write_text(table, encoding="utf-8")
    elif args.check:
        if not TABLE.is_file() or TABLE.read_text(encoding="utf-8") != table:
            print(f"{TABLE.relative_to(ROOT)} is stale: run python tools/knowrob_api.py --write", file=sys.stderr)
            return 1
    else:
        sys.stdout.write(table)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
