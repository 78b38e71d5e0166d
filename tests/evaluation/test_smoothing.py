"""The online Kneser-Ney and Witten-Bell baselines equal nltk.lm fitted on the same history."""

import random

import pytest
from nltk.lm import KneserNeyInterpolated, WittenBellInterpolated
from nltk.util import everygrams

from oracle.algorithm.records import Option, Step
from oracle.evaluation.smoothing import KN_DISCOUNT, MODIFIED, KneserNey, WittenBell, modified_discounts


def random_texts(count, seed=11):
    rng = random.Random(seed)
    for _ in range(count):
        yield [rng.choice("abcd") for _ in range(rng.randint(2, 30))], rng.choice([2, 3, 4, 5])


@pytest.mark.parametrize("ours, theirs", [(KneserNey, KneserNeyInterpolated), (WittenBell, WittenBellInterpolated)])
def test_equal_to_nltk_on_random_histories(ours, theirs):
    """On histories that start with padding (nltk's usual pipeline), every context of real tokens has
    a left neighbour, where nltk's Kneser-Ney weights are normalised; there both must agree exactly."""
    compared = 0
    for text, order in random_texts(60):
        text = ["<s>"] * (order - 1) + text
        reference = theirs(order, discount=KN_DISCOUNT) if ours is KneserNey else theirs(order)
        reference.fit([list(everygrams(text, max_len=order))], vocabulary_text=text)
        model = ours(order)
        for ch in text:
            model.observe(Step(ch))
        words = sorted(set(text) - {"<s>"}) + ["z"]  # z: never seen (nltk maps it to <UNK>)
        try:
            expected = [reference.score(w, text[-(order - 1):]) for w in words]
        except ZeroDivisionError:
            continue  # nltk divides by zero when a context was only seen at the very start
        assert model.probabilities([Option(w) for w in words]) == pytest.approx(expected, abs=1e-12)
        compared += 1
    assert compared >= 50


def test_kneser_ney_sums_to_one_where_nltk_does_not():
    # "bbcdaadcb": context b was followed by b (at the start, no left neighbour) and c; nltk weighs the
    # lower order with both raw followers and its scores sum to 1.75
    model = KneserNey(3)
    for ch in "bbcdaadcb":
        model.observe(Step(ch))
    assert sum(model.probabilities([Option(ch) for ch in "abcd"])) == pytest.approx(1.0)


def test_kneser_ney_hand_example():
    # "abab", order 2, D = 0.75: P(a | b) = max(1 - .75, 0)/1 + .75 * 1/1 * P_cont(a);
    # continuation: a is preceded by one distinct token (b), b by one (a); 2 bigram types -> P_cont = 1/2
    model = KneserNey(2)
    for ch in "abab":
        model.observe(Step(ch))
    assert model.probabilities([Option("a"), Option("b")]) == pytest.approx([0.25 + 0.375, 0.375])


def test_rejects_a_discount_outside_the_unit_interval():
    with pytest.raises(ValueError, match="discount"):
        KneserNey(3, discount=1.5)


def test_modified_discounts_follow_chen_and_goodman():
    # n1..n4 = 10, 5, 2, 1: Y = 10 / 20 = .5, D1 = 1 - 2 * .5 * 5/10 = .5, D2 = 2 - 3 * .5 * 2/5 = 1.4,
    # D3+ = 3 - 4 * .5 * 1/2 = 2
    assert modified_discounts(10, 5, 2, 1) == pytest.approx((0.5, 1.4, 2.0))
    assert modified_discounts(0, 5, 2, 1) == (KN_DISCOUNT,) * 3  # nothing seen once: the fixed discount
    assert modified_discounts(10, 5, 0, 0)[1] == KN_DISCOUNT


def test_modified_kneser_ney_estimates_from_its_counts_and_sums_to_one():
    rng = random.Random(5)
    words = [Option(ch) for ch in "abcdefg"]
    for order in (2, 3, 5):
        model = KneserNey(order, MODIFIED)
        for i in range(300):
            model.observe(Step(rng.choice("abcdefg"[:rng.randint(2, 7)])))
            if i > 3:  # once a bigram was seen (the base level counts bigram types)
                assert sum(model.probabilities(words)) == pytest.approx(1.0)
        top = model.count_of_counts[order - 1]
        raw = model.follow[order - 1]
        assert top[1] == sum(1 for c in raw.values() for n in c.values() if n == 1)
        assert model.discounts(order - 1) == modified_discounts(top[1], top[2], top[3], top[4])
        assert model.discounts(order - 1) != (KN_DISCOUNT,) * 3
