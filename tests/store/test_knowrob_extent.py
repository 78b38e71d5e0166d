"""KnowRob's extent rule, held by every backend's ``match`` (the queries Prolog asks).

mongolog (KnowRob 2.x ``src/lang/terms/triple.pl``, ``scope_intersect/5``) keeps a running
intersection of the scopes of the documents a query joins (``v_scope``, starting universal) and
drops a row once ``since < until`` fails. The reference below restates that rule; the property
says the store returns exactly the rows it keeps, for single facts and for conjunctions.
"""

from __future__ import annotations

import math

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from oracle.store import TriplePattern, Var
from oracle.store.model import USER_GRAPH, Scope
from tests.store.conftest import make_store

EX = "http://example.org/x#"
ENDS = st.sampled_from([0.0, 1.0, 2.0, 3.0, math.inf])


@st.composite
def scoped(draw: st.DrawFn) -> tuple[float, float]:
    a, b = sorted((draw(ENDS), draw(ENDS)))
    return a, b


def knowrob_keeps(scopes: list[tuple[float, float]], question: Scope | None) -> bool:
    """mongolog's rule: each document matches the question scope (the store's overlap test),
    and the intersection of all, from the universal scope, has an extent."""
    since, until = 0.0, math.inf
    for s, u in scopes:
        if question is not None and not (s <= question.until and u >= question.since):
            return False
        since, until = max(since, s), min(until, u)
        if not since < until:
            return False
    return True


@pytest.mark.parametrize("kind", ["sqlite", "mongomock"])
@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(first=st.lists(scoped(), min_size=1, max_size=4), second=st.lists(scoped(), min_size=1, max_size=3),
       question=st.none() | st.builds(lambda a, b: Scope(*sorted((a, b))), ENDS, ENDS))
def test_match_keeps_what_knowrob_keeps(kind, tmp_path_factory, first, second, question) -> None:
    store = make_store(kind, tmp_path_factory.mktemp("extent"))
    try:
        store.create_neem("n")
        rows = [(f"{EX}s", f"{EX}p", f"{EX}o{i}", USER_GRAPH, s, u) for i, (s, u) in enumerate(first)]
        rows += [(f"{EX}o{i}", f"{EX}q", f"{EX}v{j}", USER_GRAPH, s, u)
                 for i in range(len(first)) for j, (s, u) in enumerate(second)]
        store.insert("n", rows)
        one = {r["O"] for r in store.match("n", [TriplePattern(f"{EX}s", f"{EX}p", Var("O"))], scope=question)}
        assert one == {f"{EX}o{i}" for i, sc in enumerate(first) if knowrob_keeps([sc], question)}
        two = {(r["O"], r["V"]) for r in store.match(
            "n", [TriplePattern(f"{EX}s", f"{EX}p", Var("O")), TriplePattern(Var("O"), f"{EX}q", Var("V"))],
            scope=question)}
        assert two == {(f"{EX}o{i}", f"{EX}v{j}") for i, a in enumerate(first) for j, b in enumerate(second)
                       if knowrob_keeps([a, b], question)}
    finally:
        store.close()
