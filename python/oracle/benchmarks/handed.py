"""How long the hostile files of issue 54 take to be refused (target: under 1 s each, one line):
a dump whose ``.metadata.json`` is a link to /dev/zero (before: 2.7 GB read, then a MemoryError),
a FIFO in a dump and as a chains file (before: blocked for ever), a 1 KB OWL file of nested
entities for ``--soma`` (before: 160 s of rdflib's CPU) and for ``load_owl`` (before: swipl
crashed). Each runs in this process through the CLI (``oracle.cli.main``), so the times are the
refusals' own, without Python's start; the floor beside them is ``neems`` on an empty store,
the cheapest command that opens one.
"""

from __future__ import annotations

import contextlib
import io
import os
import shutil
import subprocess
import time
from pathlib import Path
from typing import Any

NESTED_OWL = (
    '<?xml version="1.0"?>\n<!DOCTYPE rdf:RDF [<!ENTITY a0 "dododododo">'
    + "".join(f'<!ENTITY a{i} "{f"&a{i - 1};" * 10}">' for i in range(1, 8))
    + ']>\n<rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#" xmlns:owl="http://www.w3.org/2002/07/owl#">'
    '<owl:Ontology rdf:about="http://x/o"><owl:versionInfo>&a7;</owl:versionInfo></owl:Ontology></rdf:RDF>\n'
)


def _timed(argv: list[str]) -> tuple[float, int, str]:
    from oracle.cli import main

    err = io.StringIO()
    began = time.perf_counter()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        try:
            code = int(main(argv) or 0)
        except SystemExit as stop:
            code = int(stop.code or 0) if isinstance(stop.code, int) else 1
    return (time.perf_counter() - began) * 1000, code, err.getvalue().strip()


def _cases(root: Path) -> list[tuple[str, list[str]]]:
    store = root / "s.sqlite"
    chains = root / "one.jsonl"
    chains.write_text('{"user": "ada", "time": "2025-03-03T08:00:00", "action": "open(fridge)"}\n')
    _timed(["import", str(chains), "--store", str(store)])
    _timed(["export", "--store", str(store), "--out", str(root / "all")])
    (neem,) = (root / "all").iterdir()
    zero, fifo = root / "zero", root / "fifo"
    shutil.copytree(neem, zero)
    shutil.copytree(neem, fifo)
    (zero / "triples" / "roslog" / "triples.metadata.json").unlink()
    (zero / "triples" / "roslog" / "triples.metadata.json").symlink_to("/dev/zero")
    (fifo / "triples" / "roslog" / "triples.bson").unlink()
    os.mkfifo(fifo / "triples" / "roslog" / "triples.bson")
    os.mkfifo(root / "chains.jsonl")
    (root / "soma").mkdir()
    (root / "soma" / "SOMA.owl").write_text(NESTED_OWL)
    return [("floor: neems", ["neems", "--store", str(store)]),
            ("load: metadata.json -> /dev/zero", ["load", str(zero), "--store", str(store), "--neem", "z"]),
            ("load: triples.bson a FIFO", ["load", str(fifo), "--store", str(store), "--neem", "f"]),
            ("import: a FIFO", ["import", str(root / "chains.jsonl"), "--store", str(store)]),
            ("ontology build --soma: nested entities", ["ontology", "build", "--soma", str(root / "soma"),
                                                        "--out", str(root / "o.owl")])]


def run(quick: bool = False) -> list[dict[str, Any]]:
    import tempfile

    rows: list[dict[str, Any]] = []
    with tempfile.TemporaryDirectory() as folder:
        root = Path(folder)
        for name, argv in _cases(root):
            ms, code, said = _timed(argv)
            print(f"  {name:42s} exit {code} in {ms:7.1f} ms: {said[:100]}", flush=True)
            rows.append({"area": "handed", "name": name, "ms": round(ms, 1), "exit": code})
        if shutil.which("swipl"):
            owl = root / "soma" / "SOMA.owl"
            began = time.perf_counter()
            done = subprocess.run(["swipl", "-q", "-g", f"use_module('{Path(__file__).resolve().parents[3] / 'prolog/lang/owl_guard'}'),"
                                   f"catch(owl_file_safe('{owl}'),E,(print_message(error,E))),halt"],
                                  capture_output=True, text=True, timeout=60)
            ms = (time.perf_counter() - began) * 1000
            print(f"  {'load_owl check (swipl, with its start)':42s} in {ms:7.1f} ms: {done.stderr.strip()[:100]}", flush=True)
            rows.append({"area": "handed", "name": "load_owl check", "ms": round(ms, 1)})
    return rows
