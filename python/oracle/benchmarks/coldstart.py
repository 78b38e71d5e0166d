"""How fast ``rank`` and the service start: ``rank`` from start to exit with nothing
kept in the user's cache (the store as the import left it) and with nothing kept anywhere, the
service's first answer for a NEEM, and the crossings between Python and Prolog a rank makes."""

from __future__ import annotations

import shutil
import tempfile
from collections.abc import Callable, Iterator
from contextlib import AbstractContextManager, contextmanager
from pathlib import Path
from typing import Any

from oracle.benchmarks.figures import installed_env, spread
from oracle.fitcache import FitCache
from oracle.historycache import HistoryCache


def rank_cli(store: Path, neem: str, grow: Callable[[], None] | None, repeat: int = 3) -> dict[str, dict[str, float]]:
    """``python -m oracle rank`` from start to exit, and the interpreter's own start and exit
    (``python -c pass``) interleaved with it: wall and CPU seconds and peak RSS (MiB) of each.
    ``rank`` starts with nothing kept in the user's cache (oracle.fitcache, oracle.historycache
    emptied), the store as the import left it (its kept view and fit, oracle.store.kept);
    ``rank_full`` with nothing kept in the store either: the whole history is read through Prolog
    and fitted. ``rank_grown`` is the robot's case: a rank made just before (untimed) kept its
    history and fit, then ``grow`` logged one more action and the next imagined situation, and
    only those are read and fitted."""
    import subprocess
    import sys

    from oracle.benchmarks.figures import run_measured

    base = [sys.executable, "-m", "oracle", "rank", "--store", str(store), "--neem", neem, "--no-write"]
    argvs = {"rank": base, "rank_full": base, "start": [sys.executable, "-c", "pass"]}
    if grow is not None:
        argvs["rank_grown"] = base
    figures: dict[str, dict[str, list[float]]] = {name: {"wall": [], "cpu": [], "rss": []} for name in argvs}
    with tempfile.TemporaryDirectory() as cache, _kept_rows(store) as kept:
        # the ontology and the compiled Prolog modules are cached as a user's are, the
        # package's bytecode written as an install writes it
        env = installed_env(NEEM_ORACLE_CACHE=cache)
        subprocess.run(base, check=True, capture_output=True, env=env)
        for _ in range(repeat):
            for name, argv in argvs.items():
                if name in ("rank", "rank_full"):
                    for folder in (FitCache.FOLDER, HistoryCache.FOLDER):
                        shutil.rmtree(Path(cache) / folder, ignore_errors=True)
                if name == "rank_grown":
                    assert grow is not None
                    subprocess.run(base, check=True, capture_output=True, env=env)
                    grow()
                with kept(name != "rank_full"):
                    wall, cpu, peak = run_measured(argv, env)
                figures[name]["wall"].append(wall)
                figures[name]["cpu"].append(cpu)
                figures[name]["rss"].append(peak / 1024)
    return {f"{name}_{kind}": spread(values) for name, by_kind in figures.items() for kind, values in by_kind.items()}


@contextmanager
def _kept_rows(store: Path) -> Iterator[Callable[[bool], AbstractContextManager[None]]]:
    """``kept(False)``: a context in which the store keeps nothing (oracle.store.kept's rows
    set aside, plain sqlite3, untimed, and put back after); ``kept(True)`` changes nothing."""
    import sqlite3

    from oracle.store.kept import TABLE

    @contextmanager
    def kept(present: bool) -> Iterator[None]:
        if present:
            yield
            return
        with sqlite3.connect(store) as conn:
            conn.execute(f"CREATE TABLE IF NOT EXISTS bench_saved AS SELECT * FROM {TABLE}")
            conn.execute(f"DELETE FROM {TABLE}")
        try:
            yield
        finally:
            with sqlite3.connect(store) as conn:
                conn.execute(f"INSERT OR REPLACE INTO {TABLE} SELECT * FROM bench_saved")
                conn.execute("DROP TABLE bench_saved")

    yield kept


def kept_floor(path: Path, neem: str) -> None:
    """The least a start from kept state reads: the NEEM's kept entries, plain sqlite3, and the
    history's JSON parsed (nothing fitted, no Prolog)."""
    import json
    import sqlite3

    from oracle.store.kept import TABLE

    conn = sqlite3.connect(path)
    for kind, data in conn.execute(f"SELECT kind, data FROM {TABLE} WHERE neem=?", (neem,)).fetchall():
        if kind == "history":
            json.loads(data)
    conn.close()


def crossings(bridge: Any, onto: Any, folder: Path) -> dict[str, int]:
    """Crossings between Python and Prolog (bridge.CROSSINGS, both ways) of one in-process rank
    with nothing kept in the user's cache (``cold``), the same rank again (``warm``), and one
    with nothing kept in the store either (``full``: its kept rows set aside)."""
    from oracle.algorithm.params import Hyperparameters
    from oracle.bridge import crossings
    from oracle.ranking import rank_neem

    counts = {}
    for name in ("cold", "warm", "full"):
        if name != "warm":
            shutil.rmtree(folder, ignore_errors=True)
        with _kept_rows(Path(bridge.store.location)) as kept, kept(name != "full"):
            before = crossings()
            rank_neem(bridge, onto, Hyperparameters(), write=False, cache=FitCache(folder / "fits"),
                      histories=HistoryCache(folder / "histories"))
            counts[name] = crossings() - before
    return counts


#: The service's first answer for a NEEM, in a process that started (the server's) with the
#: store, the ontology and the engine made: opening the NEEM's session (its view, its fit, the
#: latest situation ranked), as the page's first load asks for it.
_FIRST_ANSWER = """
import sys, time
from oracle.algorithm.params import Hyperparameters
from oracle.ontology import build_ontology
from oracle.service.engine import Engine
from oracle.store import open_store
engine = Engine(open_store(sys.argv[1]), build_ontology(), Hyperparameters())
start = time.perf_counter()
session = engine.session(sys.argv[2])
assert session.latest is not None and session.latest["ranking"]
with open(sys.argv[3], "w") as out:
    out.write(str(time.perf_counter() - start))
"""


def service_first(store: Path, neem: str, repeat: int = 3) -> dict[str, dict[str, float]]:
    """Seconds to the service's first answer for ``neem`` (``_FIRST_ANSWER``), the user's cache
    emptied before each run, and the peak RSS of its process."""
    import subprocess
    import sys

    from oracle.benchmarks.figures import run_measured

    answers, rss = [], []
    with tempfile.TemporaryDirectory() as cache:
        env = installed_env(NEEM_ORACLE_CACHE=cache)
        seconds = Path(cache) / "seconds"
        argv = [sys.executable, "-c", _FIRST_ANSWER, str(store), neem, str(seconds)]
        subprocess.run(argv, check=True, capture_output=True, env=env)  # the ontology and Prolog caches made
        for _ in range(repeat):
            for folder in (FitCache.FOLDER, HistoryCache.FOLDER):
                shutil.rmtree(Path(cache) / folder, ignore_errors=True)
            rss.append(run_measured(argv, env)[2] / 1024)
            answers.append(float(seconds.read_text()))
    return {"answer_s": spread(answers), "rss_mib": spread(rss)}


def one_more_action(store: Any, onto: Any, bridge: Any) -> Callable[[], None] | None:
    """A function that logs, as the robot does, the action chosen in the latest imagined
    situation (its first available call, 5 s after the NEEM's last end, 3 s long) and then the
    next imagined situation (the same calls); None for a NEEM without an imagined situation."""
    from oracle.neem.query import summarize_neem
    from oracle.neem.writer import NeemLogger

    if bridge.latest_situation() is None:
        return None

    def grow() -> None:
        latest = bridge.latest_situation()
        end = summarize_neem(store, bridge.neem_id).end
        begin = max(float(latest["begin"]) if end is None else end, float(latest["begin"])) + 5.0
        log = NeemLogger(store, onto, bridge.neem_id)
        log.action(latest["available"][0], begin, begin + 3.0, available=latest["available"])
        log.available(latest["available"], begin + 4.0)
        log.flush()

    return grow
