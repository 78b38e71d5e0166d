"""Each baseline on tiny hand-checked sequences, and the invariants every probability model keeps."""

import random

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from oracle.algorithm.records import Option, Step
from oracle.evaluation.baselines import BASELINES, NGram, PPMExclusion
from oracle.evaluation.lempel_ziv import LZ78, ActiveLeZi
from oracle.evaluation.smoothing import KneserNey


def fed(method, text):
    for ch in text:
        method.observe(Step(ch))
    return method


def opts(letters):
    return [Option(ch) for ch in letters]


def scores(method, letters):
    words = opts(letters)
    return method.scores(words) if hasattr(method, "scores") else method.probabilities(words)


def test_ppmc_order1_blends_the_context_with_frequencies():
    # unigram a2 b2 (2 kinds, uniform 1/3): P0 = (n + 2/3) / 6; after "b" came only "a": P = (n + 1 * P0) / 2
    got = scores(fed(NGram(1), "abab"), "abc")
    assert got == pytest.approx([(1 + 8 / 18) / 2, (4 / 9) / 2, (1 / 9) / 2])


def test_ppm_exclusion_codes_each_symbol_at_the_highest_order_that_saw_it():
    # "aaa" was followed by b and a (1 each): 1/4 each, escape 1/2; orders 2 and 1 saw only a and b
    # (excluded); order 0 without a, b: c3 d2 -> 1/2 * 3/7, 1/2 * 2/7; e takes the rest, 1/2 * 2/7
    got = scores(fed(PPMExclusion(3), "aaababbbbbaabccddcbaaaa"), "abcde")
    assert got == pytest.approx([1 / 4, 1 / 4, 3 / 14, 1 / 7, 1 / 7])


def test_lz78_predicts_from_the_phrase_being_parsed():
    # phrases a | ab | a...: in phrase "a", the parse went on to b once: (1+1)/(1+2) against (0+1)/(1+2)
    assert scores(fed(LZ78(), "aaba"), "ab") == pytest.approx([1 / 3, 2 / 3])
    # a fresh phrase node knows nothing: uniform over the alphabet
    assert scores(fed(LZ78(), "aabab"), "ab") == pytest.approx([1 / 2, 1 / 2])


def test_active_lezi_blends_the_window_contexts():
    # after aaabab: window "ab" (longest phrase 2), N(a)=4 N(b)=2 of 6; context "b" seen twice, once
    # followed by a inside the window: P(a) = 1/2 + 1/2 * 4/6, P(b) = 0 + 1/2 * 2/6
    assert scores(fed(ActiveLeZi(), "aaabab"), "ab") == pytest.approx([5 / 6, 1 / 6])


@pytest.mark.parametrize("name", sorted(set(BASELINES) - {"most_frequent", "bigram"}))  # those two rank by counts
def test_probability_models_sum_to_one_over_the_alphabet(name):
    method = BASELINES[name]()
    rng = random.Random(3)
    text = "".join(rng.choice("abcd") for _ in range(60))
    for i, ch in enumerate(text):
        method.observe(Step(ch))
        seen = "".join(sorted(set(text[: i + 1])))
        if isinstance(method, KneserNey) and i == 0:
            continue  # no bigram yet: the continuation unigram is undefined
        # LZ78 spreads its mass over the symbols seen; the others keep some for a novel one ("e")
        alphabet = seen if isinstance(method, LZ78) else seen + "e"
        assert sum(scores(method, alphabet)) == pytest.approx(1.0)


def test_idle_steps_are_context_but_never_ranked():
    method = fed(NGram(1), "ab")
    method.observe(Step("idle", idle=True))
    method.observe(Step("a"))
    method.observe(Step("idle", idle=True))
    # after <idle> came a once: a leads although b is as frequent
    assert method.rank(opts("ba"))[0] == Option("a")
    assert "<idle>" not in method.unigram


@pytest.mark.parametrize("make", list(BASELINES.values()), ids=list(BASELINES))
def test_every_baseline_keeps_the_given_order_on_ties_and_handles_an_empty_history(make):
    method = make()
    candidates = opts("cab")
    assert method.rank(candidates) == candidates
    method.observe(Step("a"))
    method.reset()
    assert method.rank(candidates) == candidates


@settings(max_examples=40, deadline=None)
@given(history=st.lists(st.sampled_from("abcdei"), max_size=40),
       candidates=st.lists(st.sampled_from("abcdefg"), min_size=1, max_size=7, unique=True))
def test_every_baseline_returns_a_permutation_of_its_candidates(history, candidates):
    offered = opts(candidates)
    for make in BASELINES.values():
        method = make()
        for ch in history:  # "i" stands for an idle delimiter
            method.observe(Step("idle", idle=True) if ch == "i" else Step(ch))
        assert sorted(map(str, method.rank(offered))) == sorted(map(str, offered))
