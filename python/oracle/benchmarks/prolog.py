"""Prolog figures: crossing cost, a 5-goal conjunction compiled vs goal-by-goal, why_not latency,
and the history read / ``rank`` / why_not at 1,000-50,000 actions against a plain SQL floor."""

from __future__ import annotations

import os
import tempfile
import time
from datetime import datetime, timedelta
from pathlib import Path
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from oracle.benchmarks.coldstart import crossings, kept_floor, one_more_action, rank_cli, service_first
from oracle.benchmarks.figures import growth_exponent, spread, spread_text
from oracle.benchmarks.ontology import SHARED_SOMA
from oracle.benchmarks.readfloor import chains_store as _chains_store
from oracle.benchmarks.readfloor import sql_floor as _sql_floor
from oracle.benchmarks.slices import slice_figures
from oracle.historycache import HistoryCache

if TYPE_CHECKING:
    from oracle.ontology.model import OdbOntology
    from oracle.store.base import Store


#: Goal-by-goal evaluation costs one store query per solution of the goals before; on the
#: 10,000-action NEEM it takes minutes, so it is timed on a NEEM of this many actions.
STEPWISE_ACTIONS = 1000


def _neem(store: Store, onto: OdbOntology, n_actions: int, neem_id: str = "bench") -> None:
    from oracle.neem.writer import NeemLogger

    log = NeemLogger.create(store, onto, user="bench", neem_id=neem_id, commit_every=500)
    tasks = ["pick(apple)", "pour(thermos, green_mug)", "pick(banana)", "open(fridge)"]
    for obj in ("apple", "thermos", "green_mug", "banana", "fridge"):
        log.perceive(obj, datetime(2024, 1, 1, 6))
    t = datetime(2024, 1, 1, 7)
    for i in range(n_actions):
        if i % 10 == 0:
            log.available(tasks[:3], t)
            log.preference([(tasks[(i // 10) % 3], 0.1), (tasks[(i // 10 + 1) % 3], 0.5)], t)
        log.action(tasks[i % 3], t + timedelta(seconds=1), t + timedelta(seconds=5))
        t += timedelta(seconds=10)
    log.flush()


def _time(fn: Callable[[], object], repeat: int = 3) -> float:
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - start)
    return best


def run(quick: bool = False) -> list[dict[str, Any]]:
    from oracle.bridge import Bridge
    from oracle.ontology import build_ontology
    from oracle.store import open_store

    n = 1000 if quick else 10000
    rows: list[dict[str, Any]] = []
    onto = build_ontology()
    with tempfile.TemporaryDirectory() as tmp:
        store = open_store(Path(tmp) / "bench.sqlite")
        start = time.perf_counter()
        _neem(store, onto, n)
        print(f"logged a {n}-action NEEM in {time.perf_counter() - start:.1f} s")
        bridge = Bridge(store, "bench", onto)

        calls = 2000
        t = _time(lambda: bridge.query(f"forall(between(1, {calls}, _), \\+ neem_store:store_match([t(x, y, _)], any))"))
        per = t / calls * 1e6
        print(f"Prolog->Python->store round trip (1-pattern store_match, no answer):{per:8.1f} us")
        rows.append({"area": "prolog", "name": "crossing", "us_per_call": per})
        t = _time(lambda: bridge.query("true"), 50) * 1e6
        print(f"Python->Prolog query('true'):                                      {t:8.1f} us")
        rows.append({"area": "prolog", "name": "python_to_prolog", "us_per_call": t})

        goal = ("executes_task(A, T), instance_of(T, odb:pick), has_participant(A, O),"
                " has_time_interval(A, I), has_interval_begin(I, B)")
        small = min(n, STEPWISE_ACTIONS)
        if small < n:
            _neem(store, onto, small, "bench-small")
        for label, stepwise, neem, size in (("compiled (one query)", False, "bench", n),
                                            ("compiled (one query)", False, "bench-small", small),
                                            ("goal-by-goal", True, "bench-small", small)):  # fmt: skip
            if neem == "bench-small" and small == n:
                neem = "bench"
                if not stepwise:
                    continue
            b = bridge if neem == "bench" else Bridge(store, neem, onto)
            result: list[Any] = []
            t = _time(lambda: result.append(len(b.solutions(goal, ["A", "O", "B"], stepwise=stepwise))), 1)
            print(f"5-goal conjunction, {label:22s} on {size:,} actions: {t * 1000:8.1f} ms  ({result[-1]} solutions)")
            rows.append({"area": "prolog", "name": f"conjunction {label}", "ms": t * 1000,
                         "solutions": result[-1], "actions": size})
        bridge = Bridge(store, "bench", onto)

        latest = bridge.query("aggregate_all(max(B), odb_decisions:decision(situation, _, B), M)")[0]["M"]
        for label, at in (("lately", None), ("at a time", latest - 1000)):
            t = _time(lambda: bridge.why_not("pick", ["banana"], at), 3)
            print(f"why_not(pick(banana)) {label:10s}: {t * 1000:8.1f} ms (target < 100 ms)")
            rows.append({"area": "prolog", "name": f"why_not {label}", "ms": t * 1000, "actions": n})
        bridge.close()
        store.close()
    rows.extend(history_figures(quick))
    rows.extend(slice_figures(quick))
    rows.extend(owl_figures(quick))
    return rows


# -- OWL reasoning with the full SOMA loaded ----------------------------------------
#: The official SOMA/DUL files: the ontology bench's folder, or ``$NEEM_SOMA_DIR``.
SOMA_DIR = Path(os.environ.get("NEEM_SOMA_DIR") or SHARED_SOMA)
#: kb_call goals over the OWL predicates, each compiled into one store query, and what they ask.
OWL_QUERIES = (
    ("subclass_of(soma:'Pouring', only(P, R))", "the `only` restrictions of a SOMA class (all solutions)"),
    ("executes_task(A, T), instance_of(T, only(P, R))", "the `only` restrictions an action's task is under (A bound)"),
    ("is_restriction(X, exactly(P, N, C))", "every qualified cardinality restriction of SOMA/DUL"),
)  # fmt: skip
#: The floor: one one-pattern store query through the same crossing (a class's direct superclasses).
OWL_FLOOR = "triple(soma:'Pouring', rdfs:subClassOf, X)"


def owl_figures(quick: bool = False, repeat: int = 7) -> list[dict[str, Any]]:
    """kb_call over the OWL predicates on a NEEM logged with the official SOMA/DUL TBox (10,000
    actions; 1,000 when quick), min/median/max of ``repeat`` runs of each query, beside the floor
    (a one-pattern kb_call) measured in the same run."""
    from oracle.bridge import Bridge
    from oracle.ontology import build_ontology
    from oracle.store import open_store

    if not (SOMA_DIR / "SOMA.owl").exists():
        print(f"OWL kb_call: skipped, no official SOMA/DUL at {SOMA_DIR} (set NEEM_SOMA_DIR)")
        return []
    n = 1000 if quick else 10000
    rows: list[dict[str, Any]] = []
    onto = build_ontology(soma_dir=SOMA_DIR)
    with tempfile.TemporaryDirectory() as tmp:
        store = open_store(Path(tmp) / "owl.sqlite")
        _neem(store, onto, n)
        bridge = Bridge(store, "bench", onto)
        (first,) = bridge.query("once(kb_call((executes_task(A, T), instance_of(T, odb:pick)))), atom_string(A, S)")
        action = first["S"].decode() if isinstance(first["S"], bytes) else str(first["S"])

        def timed(goal: str) -> tuple[dict[str, float], int]:
            text = f"A = '{action}', findall(x, kb_call(({goal})), L), length(L, N)"
            counts: list[int] = []
            samples = []
            bridge.query(text)  # warm: compile and the store's page cache
            for _ in range(repeat):
                start = time.perf_counter()
                counts.append(bridge.query(text)[0]["N"])
                samples.append(time.perf_counter() - start)
            return spread(samples), counts[-1]

        floor, _ = timed(OWL_FLOOR)
        print(f"OWL kb_call on {n:,} actions with the official SOMA/DUL TBox, ms min/median/max of {repeat} "
              f"(floor: one-pattern kb_call {spread_text(floor, 1000)} ms)")
        for goal, what in OWL_QUERIES:
            figure, solutions = timed(goal)
            print(f"  {goal:52s} {spread_text(figure, 1000)} ms  {solutions:5d} solutions  "
                  f"({figure['median'] / floor['median']:.1f}x floor; {what})")
            rows.append({"area": "prolog", "name": f"owl kb_call {goal}", "actions": n, "solutions": solutions,
                         "ms": figure["median"] * 1000, "min_ms": figure["min"] * 1000, "max_ms": figure["max"] * 1000,
                         "floor_ms": floor["median"] * 1000})
        bridge.close()
        store.close()
    return rows


# -- the history read and rank at NEEM sizes a user meets ---------------------------
#: NEEM sizes (executed actions) of the history figures; quick runs stop at the first two.
HISTORY_SIZES = (1000, 10000, 50000)


_spread, _exponent = spread, growth_exponent


def _fmt(figure: dict[str, float], unit: float = 1.0, digits: int = 3) -> str:
    """A spread as min/median/max, three digits unless told (the history figures are seconds)."""
    return spread_text(figure, unit, digits)


def _tail_reads(bridge: Any, n: int, begins: list[float]) -> list[dict[str, Any]]:
    """The read of the last 1, 100 and 400 actions of the history (``Bridge.history_view(after)``, what
    extends a kept view; ``begins``: the rows' begins of the whole read): wall seconds, min/median/max
    of 3, in process."""
    out = []
    for last in (1, 100, 400):
        after = begins[-last - 1]
        wall, _ = _timed(lambda: bridge.history_view(after))
        print(f"history read of the last {last:>3} actions, {n:>6,} actions: wall {_fmt(wall)} s (min/median/max)", flush=True)
        out.append({"area": "prolog", "name": f"history read of the last {last}", "actions": n, "wall_s": wall})
    return out


def _timed(fn: Callable[[], object], repeat: int = 3) -> tuple[dict[str, float], dict[str, float]]:
    """Wall and CPU seconds of ``repeat`` calls (CPU: this process, Prolog included)."""
    walls, cpus = [], []
    for _ in range(repeat):
        w, c = time.perf_counter(), time.process_time()
        fn()
        walls.append(time.perf_counter() - w)
        cpus.append(time.process_time() - c)
    return _spread(walls), _spread(cpus)


def _crossing_goal(bridge: Any) -> str:
    """The least a question costs: one compiled store query of one pattern and one row, the
    interval of one event (its subject known, so the (s, p) index finds the row). An unbound
    subject with ``limit(1)`` was no floor while a limit sorted its matches by id (56 ms at
    50,000 actions until 2026-12-07); a known subject is the floor either way."""
    from oracle.bridge.values import plain, quote_atom

    subject = bridge.query("kb_iri(dul:hasTimeInterval, P), once(store_match([t(S, P, _)], any, [limit(1)]))")[0]["S"]
    return f"kb_iri(dul:hasTimeInterval, P), once(store_match([t({quote_atom(plain(subject))}, P, _)], any, [limit(1)]))"


def history_figures(quick: bool = False) -> list[dict[str, Any]]:
    """History read (in process), its SQL floor, ``rank`` start to exit and why_not, per size;
    the growth exponents; and at 10,000 actions whether the read equals the first
    implementation's (prolog/fixtures/history_reference.pl)."""
    from oracle.bridge import Bridge
    from oracle.ontology import build_ontology
    from oracle.paths import prolog_dir
    from oracle.store import open_store

    sizes = list(HISTORY_SIZES[:2] if quick else HISTORY_SIZES)
    if quick:
        sizes = [1000, 4000]
    rows: list[dict[str, Any]] = []
    onto = build_ontology()
    medians: dict[str, list[float]] = {"history_cpu": [], "rank_wall": [], "rank_cpu": [], "floor": []}
    with tempfile.TemporaryDirectory() as tmp:
        start = time.perf_counter()
        path = _chains_store(Path(tmp), sizes)
        print(f"imported NEEMs of {', '.join(map(str, sizes))} actions in {time.perf_counter() - start:.0f} s", flush=True)
        store = open_store(path)
        for n in sizes:
            neem = f"u{n}"
            bridge = Bridge(store, neem, onto)
            read: dict[str, list[Any]] = {}  # the last read's rows (their begins: _tail_reads)
            wall, cpu = _timed(lambda: read.update(rows=bridge.history()))
            history = [len(read["rows"])]
            _, floor = _timed(lambda: _sql_floor(path, bridge.neem_id))  # tables are named by the id
            ratio = cpu["median"] / floor["median"]
            print(f"history read, {n:>6,} actions ({history[-1]} rows): wall {_fmt(wall)} s, cpu {_fmt(cpu)} s"
                  f" (min/median/max); SQL floor cpu {_fmt(floor)} s; cpu/floor {ratio:.1f}x", flush=True)
            rows.extend(_tail_reads(bridge, n, [row["begin"] for row in read.pop("rows")]))
            bridge.why_not("pick", ["banana"])  # the first question loads nothing more; time the ones after
            why_wall, why_cpu = _timed(lambda: bridge.why_not("pick", ["banana"]), 5)
            crossing = _crossing_goal(bridge)
            _, cross_cpu = _timed(lambda: bridge.query(crossing), 5)
            why_ratio = why_cpu["median"] / max(cross_cpu["median"], 1e-6)
            print(f"why_not(pick(banana)) in process, {n:>6,} actions: wall {_fmt(why_wall, 1000, 1)} ms,"
                  f" cpu {_fmt(why_cpu, 1000, 1)} ms (min/median/max of 5); floor, one one-row store query:"
                  f" cpu {_fmt(cross_cpu, 1000, 1)} ms; {why_ratio:.1f}x floor"
                  f" (target <= {50 if n <= 10000 else 200} ms)", flush=True)
            # before rank_cli grows the NEEM: the store as the import left it
            counts = crossings(bridge, onto, Path(tmp) / f"crossings{n}")
            print(f"crossings Python<->Prolog per rank, {n:>6,} actions: cold {counts['cold']}, warm {counts['warm']}"
                  f" (target <= 6 / <= 2); with nothing kept in the store either {counts['full']}", flush=True)
            cli = rank_cli(path, neem, one_more_action(store, onto, bridge))
            # Floors of a rank from start to exit: the interpreter starting and exiting, plus the
            # plain SQL read of what it needs (both measured in this run): the kept entries
            # (``rank``), the rows the whole history needs (``rank_full``).
            _, kept_s = _timed(lambda: kept_floor(path, bridge.neem_id))
            rank_floor = cli["start_cpu"]["median"] + kept_s["median"]
            full_floor = cli["start_cpu"]["median"] + floor["median"]
            rank_ratio = cli["rank_cpu"]["median"] / rank_floor
            target = 1 if n <= 10000 else 2
            print(f"rank start to exit, nothing kept in the user's cache (the store's kept view and fit: from the"
                  f" import, runs 2-3 after 1-2 more actions),"
                  f" {n:>6,} actions: wall {_fmt(cli['rank_wall'])} s, cpu {_fmt(cli['rank_cpu'])} s, peak RSS"
                  f" {_fmt(cli['rank_rss'], 1, 0)} MiB (min/median/max of 3); floor (python -c pass cpu"
                  f" {_fmt(cli['start_cpu'])} s + the kept entries read with plain SQL {_fmt(kept_s)} s)"
                  f" {rank_floor:.3f} s cpu; {rank_ratio:.1f}x floor cpu (target <= {target} s"
                  f"{', <= 250 MiB' if n >= 50000 else ''})", flush=True)
            print(f"rank start to exit, nothing kept in the store either (the whole history read and fitted),"
                  f" {n:>6,} actions: wall {_fmt(cli['rank_full_wall'])} s, cpu {_fmt(cli['rank_full_cpu'])} s, peak"
                  f" RSS {_fmt(cli['rank_full_rss'], 1, 0)} MiB; floor (python -c pass + SQL floor) {full_floor:.3f} s"
                  f" cpu; {cli['rank_full_cpu']['median'] / full_floor:.1f}x floor cpu", flush=True)
            if n in (10000, max(sizes)):
                first = service_first(path, neem)
                print(f"service's first answer for the NEEM (session opened: view, fit, latest situation ranked),"
                      f" {n:>6,} actions: {_fmt(first['answer_s'])} s, peak RSS {_fmt(first['rss_mib'], 1, 0)} MiB"
                      f" (min/median/max of 3; floor: the kept entries read with plain SQL {_fmt(kept_s)} s;"
                      f" target <= 1 s at 10,000)", flush=True)
                rows.append({"area": "prolog", "name": "service first answer", "actions": n, **first,
                             "kept_floor_s": kept_s})
            rows.append({"area": "prolog", "name": "crossings per rank", "actions": n, **counts})
            if "rank_grown_wall" in cli:
                print(f"rank start to exit after one more action was logged (history and fit of the rest kept),"
                      f" {n:>6,} actions:"
                      f" wall {_fmt(cli['rank_grown_wall'])} s, cpu {_fmt(cli['rank_grown_cpu'])} s;"
                      f" {cli['rank_grown_cpu']['median'] / rank_floor:.1f}x floor cpu"
                      f" (target <= {target} s)", flush=True)
                medians.setdefault("rank_grown_wall", []).append(cli["rank_grown_wall"]["median"])
            medians["history_cpu"].append(cpu["median"])
            medians["rank_wall"].append(cli["rank_wall"]["median"])
            medians["rank_cpu"].append(cli["rank_cpu"]["median"])
            medians["floor"].append(floor["median"])
            rows.append({"area": "prolog", "name": "history read", "actions": n, "rows": history[-1],
                         "wall_s": wall, "cpu_s": cpu, "sql_floor_s": floor, "floor_ratio": ratio,
                         "why_not_ms": {k: v * 1000 for k, v in why_wall.items()},
                         "why_not_cpu_ms": {k: v * 1000 for k, v in why_cpu.items()},
                         "why_not_floor_cpu_ms": {k: v * 1000 for k, v in cross_cpu.items()},
                         "why_not_floor_ratio": why_ratio,
                         "rank_wall_s": cli["rank_wall"], "rank_cpu_s": cli["rank_cpu"], "rank_rss_mib": cli["rank_rss"],
                         "rank_floor_cpu_s": rank_floor, "rank_floor_ratio": rank_ratio,
                         "rank_full_wall_s": cli["rank_full_wall"], "rank_full_cpu_s": cli["rank_full_cpu"],
                         "rank_full_rss_mib": cli["rank_full_rss"], "rank_full_floor_cpu_s": full_floor,
                         "rank_grown_wall_s": cli.get("rank_grown_wall"), "rank_grown_cpu_s": cli.get("rank_grown_cpu"),
                         "start_wall_s": cli["start_wall"], "start_cpu_s": cli["start_cpu"]})
            if n == 10000:
                fixture = prolog_dir() / "fixtures" / "history_reference.pl"
                same = bridge.query(f"use_module('{fixture}'), odb_history:situation_history(New),"
                                    " history_reference:situation_history_reference(Old),"
                                    " ( New == Old -> S = true ; S = false )")[0]["S"]
                print(f"history read at 10,000 actions equals the first implementation's: {same}", flush=True)
                rows.append({"area": "prolog", "name": "history equals reference", "actions": n, "equal": same == "true"})
                grow = one_more_action(store, onto, bridge)
                if grow is not None:
                    kept = HistoryCache(Path(tmp) / "kept")
                    kept.history(bridge)
                    grow()
                    equal = kept.history(bridge) == bridge.history()
                    print(f"kept history after one more action equals the whole read at 10,000 actions: {equal}",
                          flush=True)
                    rows.append({"area": "prolog", "name": "kept history equals whole read", "actions": n,
                                 "equal": equal})
            bridge.close()
        for key, label in (("history_cpu", "history read cpu"), ("rank_wall", "rank wall"), ("rank_cpu", "rank cpu"),
                           ("rank_grown_wall", "rank wall after one more action"), ("floor", "SQL floor")):
            k = _exponent(sizes, medians[key]) if len(medians.get(key, ())) == len(sizes) else None
            if k is not None:
                print(f"growth exponent, {label}, {sizes[-2]:,} -> {sizes[-1]:,}: {k:.2f} (n log n ~ 1.1)", flush=True)
                rows.append({"area": "prolog", "name": f"growth {label}", "exponent": k,
                             "sizes": sizes[-2:]})
        store.close()
    return rows
