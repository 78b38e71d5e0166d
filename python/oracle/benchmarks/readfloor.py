"""What the history-read benchmarks read and their floor: a store of NEEMs imported as a user
would (``chains_store``) and the same rows read with plain SQL (``sql_floor``); shared by the
prolog area and its whole-read-in-slices figures (benchmarks/prolog.py, benchmarks/slices.py)."""

from __future__ import annotations

from pathlib import Path
from typing import Any


def chains_store(tmp: Path, sizes: list[int]) -> Path:
    """A store with one imported NEEM ``u<N>`` per size: the first N rows of one simulated
    persona (the world generator's chains, ~20 available tasks per decision), imported through
    the CLI as a user would."""
    import subprocess
    import sys

    days = max(sizes) // 35 + 30
    gen = tmp / "gen"
    subprocess.run([sys.executable, "-m", "oracle", "generate", "--personas", "1", "--days", str(days),
                    "--seed", "3", "--out", str(gen)], check=True, capture_output=True)
    rows = [line for name in ("tune.jsonl", "test.jsonl") for line in (gen / name).read_text().splitlines() if line]
    store = tmp / "history.sqlite"
    for n in sizes:
        if len(rows) < n:
            raise RuntimeError(f"the simulation gave {len(rows)} actions, fewer than {n}")
        path = tmp / f"u{n}.jsonl"
        with path.open("w") as out:
            for line in rows[:n]:
                out.write(line.replace(line[line.index('"user"'):line.index(',', line.index('"user"'))],
                                       f'"user": "u{n}"') + "\n")
        subprocess.run([sys.executable, "-m", "oracle", "import", str(path), "--store", str(store),
                        "--commit-every", "1000"], check=True, capture_output=True)
    return store


def sql_floor(path: Path, neem: str) -> tuple[int, int, int]:
    """The rows the history read needs, read with plain SQL (exact properties, no closures, no
    Prolog): actions with task, type and interval; interval types; imaginings with begin and
    imagined tasks. Returns the number of rows of each of the three."""
    import sqlite3

    conn = sqlite3.connect(path)
    names: dict[Any, Any] = {}

    def name(term_id: Any) -> Any:
        """The IRI of a term id, looked up once (the terms table is shared by every NEEM)."""
        if term_id not in names:
            row = conn.execute("SELECT value FROM terms WHERE id=?", (term_id,)).fetchone()
            names[term_id] = row[0] if row else term_id
        return names[term_id]

    iri = {
        "exec": "http://www.ontologydesignpatterns.org/ont/dul/DUL.owl#executesTask",
        "hti": "http://www.ontologydesignpatterns.org/ont/dul/DUL.owl#hasTimeInterval",
        "begin": "http://www.ease-crc.org/ont/SOMA.owl#hasIntervalBegin",
        "end": "http://www.ease-crc.org/ont/SOMA.owl#hasIntervalEnd",
        "type": "http://www.w3.org/1999/02/22-rdf-syntax-ns#type",
        "imag": "https://ontology.dlr.de/soma/odb#imagines_situation",
        "plan": "http://www.ease-crc.org/ont/SOMA.owl#isPlanFor",
    }
    ids = {}
    for key, value in iri.items():
        row = conn.execute("SELECT id FROM terms WHERE value=?", (value,)).fetchone()
        ids[key] = row[0] if row else -1
    t = f'"{neem}_triples"'
    # An imagining's plans live in the NEEM's side table where it has one (docs/store.md).
    has_side = conn.execute("SELECT 1 FROM sqlite_master WHERE type='table' AND name=?", (f"{neem}_side",)).fetchone()
    side = f'"{neem}_side"' if has_side else t

    def drive(alias: str, key: str) -> str:
        """The driving pattern through the property-closure index, as the store's compiler does."""
        return f"{alias}.pstar IN (SELECT cid FROM closure_member WHERE value=:{key}) AND {alias}.p NOT IN (1, 2, 3)"
    queries = [
        f"SELECT a.s, a.o, ty.o, b.o, e.o FROM {t} a JOIN {t} ty ON ty.s=a.o AND ty.p=:type "
        f"JOIN {t} i ON i.s=a.s AND i.p=:hti JOIN {t} b ON b.s=i.o AND b.p=:begin "
        f"JOIN {t} e ON e.s=i.o AND e.p=:end WHERE a.p=:exec AND {drive('a', 'exec')}",
        f"SELECT i.s, ty.o FROM {t} i JOIN {t} ty ON ty.s=i.o AND ty.p=:type WHERE i.p=:hti AND {drive('i', 'hti')}",
        f"SELECT b.o, pt.o FROM {t} m JOIN {t} i ON i.s=m.s AND i.p=:hti JOIN {t} b ON b.s=i.o AND b.p=:begin "
        f"JOIN {side} pl ON pl.s=m.s AND pl.p=:imag JOIN {t} pt ON pt.s=pl.o AND pt.p=:plan"
        f" WHERE m.p=:hti AND {drive('m', 'hti')}",
    ]
    counts = []
    for sql in queries:
        count = 0
        for row in conn.execute(sql, ids):
            [name(v) if isinstance(v, int) else v for v in row]
            count += 1
        counts.append(count)
    conn.close()
    actions, interval_types, imagined = counts
    return actions, interval_types, imagined
