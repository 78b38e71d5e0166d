"""Ontology figures: build time of the sample kitchen and the cost of the distance matrix."""

from __future__ import annotations

from typing import Any

import time
from pathlib import Path

from oracle.ontology import DistanceMatrix, build_with_report

SHARED_SOMA = Path(__file__).resolve().parents[4] / "shared" / "soma"


def run(quick: bool = False) -> list[dict[str, Any]]:
    rows = []
    sources: list[tuple[str, Path | None]] = [("core TBox", None)]
    if (SHARED_SOMA / "SOMA.owl").exists() and not quick:
        sources.append(("official SOMA/DUL", SHARED_SOMA))
    for label, soma in sources:
        start = time.perf_counter()
        onto, report = build_with_report(soma_dir=soma)
        built = time.perf_counter() - start
        start = time.perf_counter()
        matrix = DistanceMatrix.compute(onto.taxonomy)
        computed = time.perf_counter() - start
        n = len(matrix.classes)
        print(f"{label:18s} build {built * 1000:8.1f} ms  {report.n_triples:6d} triples  "
              f"distance matrix {n}x{n} in {computed * 1000:7.1f} ms")
        rows.append({"area": "ontology", "name": f"build+matrix ({label})", "build_ms": built * 1000,
                     "matrix_ms": computed * 1000, "classes": n, "triples": report.n_triples})
    return rows
