"""Benchmarks: one module per area, each exposing ``run(quick: bool) -> list[dict]``.

A module prints its figures as it measures them and returns them as rows (each with at least
``area`` and ``name``); ``python -m oracle bench`` runs them in ``AREAS`` order.
"""

AREAS = ("ontology", "store", "prolog", "algorithm", "evaluation", "service", "security", "querylimits", "handed", "flood",
         "rosprolog", "past", "explore", "prior", "cli")
