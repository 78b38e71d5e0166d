"""KnowRob 2.x's own plunit units, run unchanged over prolog/ on every backend (the memory backend
in plain swipl, SQLite and the Mongo code path through the bridge). See knowrob_units.py.

    .venv/bin/pytest -q -s tests/prolog/test_knowrob_own_tests.py      # prints the scores
"""

from __future__ import annotations

import itertools
import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from oracle.bridge import MODULES, Bridge
from oracle.paths import prolog_dir
from oracle.store import open_store
from oracle.store.mongo import MongoStore
from tests.prolog.knowrob_units import RESTATED, UNITS, KnowRobSource, Unit, units, write_units

HARNESS = prolog_dir() / "compat" / "knowrob_tests.pl"
#: The share of KnowRob's units' tests (blocked and fixme ones left out) that must pass.
TARGET = 0.90


@pytest.fixture(scope="module")
def source():
    found = KnowRobSource.find()
    if found is None:
        pytest.skip("no KnowRob source (KNOWROB_SRC, or the git mirror at KNOWROB_GIT)")
    return found


@pytest.fixture(scope="module")
def unit_files(source, tmp_path_factory):
    folder = tmp_path_factory.mktemp("knowrob_units")
    found = units(source, UNITS + RESTATED)
    packages = source.package_path(tmp_path_factory.mktemp("packages"))
    return found, write_units(found, folder), packages


_SCORE = re.compile(r"^unit (\S+) (\d+) (\d+) (\d+) (\d+)$", re.M)


def _scores(text: str) -> dict[str, tuple[int, int, int, int]]:
    return {m.group(1): tuple(int(g) for g in m.groups()[1:]) for m in _SCORE.finditer(text)}  # type: ignore[misc]


def _run_goal(files: list[Path], names: list[str]) -> str:
    """The Prolog goal that loads the units, runs them and prints `unit Name P F B X` lines."""
    loads = ",".join(f"'{f}'" for f in files)
    units_list = ",".join(f"'{n}'" for n in names)
    return (f"load_files([{loads}], []), set_test_options([silent(true)]), "
            f"forall(member(U, [{units_list}]), ( ( catch(run_tests(U), _, true) -> true ; true ), "
            "knowrob_units_score(U, score(P, F, B, X)), format('unit ~w ~w ~w ~w ~w~n', [U, P, F, B, X]) ))")


def _report(backend: str, found: list[Unit], scores: dict[str, tuple[int, int, int, int]]) -> tuple[int, int]:
    mirrored = {u.name for u in found if u.source in UNITS}
    lines = []
    totals = {"units": [0, 0, 0, 0], "restated": [0, 0, 0, 0]}
    for unit in found:
        p, f, b, x = scores.get(unit.name, (0, 0, 0, 0))
        key = "units" if unit.name in mirrored else "restated"
        for i, v in enumerate((p, f, b, x)):
            totals[key][i] += v
        lines.append(f"  {unit.source:42} {unit.name:28} passed {p:3} failed {f:3} blocked {b} fixme {x}")
    print(f"\nKnowRob's own units on {backend}:\n" + "\n".join(lines))
    for key, (p, f, b, x) in totals.items():
        print(f"{backend} {key}: {p} passed of {p + f} run ({b} blocked, {x} fixme, as KnowRob marks them)")
    p, f, _, _ = totals["units"]
    return p, p + f


@pytest.mark.skipif(shutil.which("swipl") is None, reason="needs swipl")
def test_knowrob_units_on_the_memory_backend(unit_files):
    found, files, packages = unit_files
    modules = ",".join(f"'{prolog_dir() / f'{m}.pl'}'" for m in MODULES)
    goal = (f"maplist([F]>>use_module(user:F), [{modules}]), use_module(user:'{HARNESS}'), "
            + _run_goal(files, [u.name for u in found]))
    env = dict(os.environ, KNOWROB_PACKAGE_PATH=str(packages))
    done = subprocess.run(["swipl", "-q", "-g", goal, "-t", "halt"], capture_output=True, text=True, timeout=900, env=env)
    scores = _scores(done.stdout)
    assert scores, done.stdout[-3000:] + done.stderr[-3000:]
    passed, run = _report("memory", found, scores)
    assert passed >= TARGET * run, f"{passed}/{run}"


def _sqlite(tmp_path):
    return open_store(tmp_path / "k.sqlite")


def _mongomock(_):
    import mongomock_ng

    return MongoStore(mongomock_ng.MongoClient(), "kown")


# mongomock-ng answers KnowRob's units in ~30 s (its $lookup is slow): with the slow tests
@pytest.mark.parametrize("make_store", [_sqlite, pytest.param(_mongomock, marks=pytest.mark.slow)], ids=["sqlite", "mongomock"])
def test_knowrob_units_on_the_python_stores(unit_files, make_store, tmp_path, monkeypatch):
    from pyswip import Atom, Prolog

    found, files, packages = unit_files
    monkeypatch.setenv("KNOWROB_PACKAGE_PATH", str(packages))
    store = make_store(tmp_path)
    store.create_neem("k")
    bridge = Bridge(store, "k")
    ids = itertools.count(1)

    def py_fresh_neem(out):
        neem = f"kown{next(ids)}"
        store.create_neem(neem)
        out.unify(Atom(neem))
        return True

    try:
        Prolog.register_foreign(py_fresh_neem, arity=1, module="neem_store")
        bridge.query(f"use_module(user:'{HARNESS}')")
        bridge.query("retractall(knowrob_2x:fresh_store_hook), "
                     "assertz((knowrob_2x:fresh_store_hook :- neem_store:py_fresh_neem(Id), store_use_python(Id)))")
        names = [u.name for u in found]
        bridge.query(f"load_files([{','.join(repr(str(f)) for f in files)}], []), set_test_options([silent(true)])")
        scores = {}
        for name in names:
            bridge.query(f"( catch(run_tests('{name}'), _, true) -> true ; true )")
            (row,) = bridge.query(f"knowrob_units_score('{name}', score(P, F, B, X))")
            scores[name] = (row["P"], row["F"], row["B"], row["X"])
    finally:
        bridge.query("retractall(knowrob_2x:fresh_store_hook)")
        bridge.close()
        store.close()
    passed, run = _report(type(store).__name__, found, scores)
    assert passed >= TARGET * run, f"{passed}/{run}"
