"""A ranking the online predictors re-weigh takes the used variants' evidence from every
variant's evidence of the same offer (``OnlineOracle._used_evidence``), which it reads next
anyway: the rankings are those of the used variants computed alone, with one evidence pass less."""

from __future__ import annotations

from oracle.algorithm.personal import PersonalOracle
from oracle.algorithm.routine import RoutineOracle
from oracle.benchmarks.algorithm import history


def _passes(model, query) -> int:
    """How many evidence passes (``_variant_probabilities``) ranking ``query`` makes."""
    count = [0]
    inner = model._variant_probabilities

    def counted(*args, **kwargs):
        count[0] += 1
        return inner(*args, **kwargs)

    model._variant_probabilities = counted
    try:
        model.__dict__.pop("_evidence_at", None)  # nothing kept from an earlier ranking
        model.rank(query, tree_roots=0)
    finally:
        del model._variant_probabilities
    return count[0]


def test_a_reweighed_ranking_is_the_one_of_the_used_variants_alone_with_one_pass_less():
    matrix, steps = history(500, seed=7)
    model = PersonalOracle(matrix).fit(steps[:450])  # the default predictor
    compared = 0
    for query in steps[450:]:
        if len(query.options) < 2 or not model.serves():
            continue
        model.__dict__.pop("_evidence_at", None)
        shared = model.rank(query, tree_roots=0)
        model.__dict__.pop("_evidence_at", None)
        model._used_evidence = lambda *a: RoutineOracle._used_evidence(model, *a)  # the used variants alone
        try:
            alone = model.rank(query, tree_roots=0)
        finally:
            del model._used_evidence
        assert [(t.option, t.probability, t.n_similar, t.context) for t in shared.tasks] == \
            [(t.option, t.probability, t.n_similar, t.context) for t in alone.tasks]
        assert _passes(model, query) == 1  # every variant's evidence once (it was 2: the used ones, then all)
        compared += 1
    assert compared > 20
