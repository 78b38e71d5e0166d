"""Lempel-Ziv family baselines: the LZ78 predictor and Active LeZi, updated online.

Both read the same token sequence as the other baselines (tokens.py). Formulas and references:
docs/evaluation.md.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Sequence
from dataclasses import dataclass, field

from oracle.algorithm.records import Option, Step
from oracle.evaluation.tokens import order_by_score, token


@dataclass
class _Node:
    # how often the node was entered (LZ78) or was a suffix of the window (Active LeZi)
    count: int = 0
    # how often a symbol followed it: LZ78 transitions out of the node, Active LeZi within the window
    followed: int = 0
    children: dict[object, _Node] = field(default_factory=dict)


class LZ78:
    """The LZ78 predictor (Langdon 1983; as compared in Begleiter, El-Yaniv & Yona 2004).

    The history is parsed into LZ78 phrases (each the shortest string not yet in the dictionary).
    The next symbol is predicted from the phrase parsed so far, i.e. the current trie node v:
    P(s) = (N(v s) + 1) / (sum_x N(v x) + |alphabet|), N(v s) counting how often the parse went from v to v s.
    """

    name = "lz78"

    def __init__(self) -> None:
        self.reset()

    def reset(self) -> None:
        self.root = _Node()
        self.node = self.root
        self.alphabet: set[object] = set()

    def observe(self, step: Step) -> None:
        symbol = token(step)
        self.alphabet.add(symbol)
        child = self.node.children.get(symbol)
        self.node.followed += 1
        if child is None:
            # a new phrase ends here: add it to the dictionary and start the next phrase at the root
            self.node.children[symbol] = _Node(count=1)
            self.node = self.root
        else:
            child.count += 1
            self.node = child

    def probabilities(self, words: Sequence[object]) -> list[float]:
        node = self.node
        size = max(1, len(self.alphabet))
        out = []
        for w in words:
            child = node.children.get(w)
            out.append(((child.count if child else 0) + 1) / (node.followed + size))
        return out

    def rank(self, candidates: Sequence[Option], time_of_day: str | None = None, at: float | None = None) -> list[Option]:
        return order_by_score(candidates, self.probabilities(candidates))


class ActiveLeZi:
    """Active LeZi (Gopalratnam & Cook 2007): LZ78 phrases set a window length, every suffix of the
    sliding window is counted, and prediction blends the window's contexts PPM-style.

    The window holds the last L symbols, L the longest LZ78 phrase so far. With N(x) the number of
    times x was a suffix of the window and t the number of symbols seen,
    P_0(s) = N(s) / t and, for the window's contexts c_k of length k = 1 .. L-1 in turn,
    P_k(s) = N(c_k s) / N(c_k) + e(c_k) * P_(k-1)(s), e(c_k) = (N(c_k) - sum_s N(c_k s)) / N(c_k).
    """

    name = "alz"

    def __init__(self) -> None:
        self.reset()

    def reset(self) -> None:
        self.seen = 0
        self.phrases = _Node()  # the LZ78 dictionary
        self.phrase = self.phrases
        self.longest = 0
        self.depth = 0
        self.window: deque[object] = deque()
        # counts of window suffixes, stored reversed (newest symbol first) so one walk updates them all
        self.suffixes = _Node()

    def observe(self, step: Step) -> None:
        symbol = token(step)
        self.seen += 1
        child = self.phrase.children.get(symbol)
        if child is None:
            self.phrase.children[symbol] = _Node()
            self.longest = max(self.longest, self.depth + 1)
            self.phrase, self.depth = self.phrases, 0
        else:
            self.phrase, self.depth = child, self.depth + 1
        self.window.append(symbol)
        while len(self.window) > self.longest:
            self.window.popleft()
        node = self.suffixes
        for s in reversed(self.window):
            node = node.children.setdefault(s, _Node())
            node.count += 1
        # the suffixes of the window before this symbol are the contexts it just followed
        node = self.suffixes
        for i in range(len(self.window) - 2, -1, -1):
            node = node.children[self.window[i]]
            node.followed += 1

    def probabilities(self, words: Sequence[object]) -> list[float]:
        if not self.seen:
            return [0.0] * len(words)
        window = list(self.window)
        probs = []
        for w in words:
            # reversed path w, newest, ..., oldest: the node at depth k + 1 counts the context of length k followed by w
            top = self.suffixes.children.get(w)
            p = top.count / self.seen if top else 0.0
            node_w = top
            node_c = self.suffixes
            for k in range(1, len(window)):
                node_c = node_c.children[window[-k]]
                node_w = node_w.children.get(window[-k]) if node_w is not None else None
                escape = (node_c.count - node_c.followed) / node_c.count
                p = (node_w.count if node_w is not None else 0) / node_c.count + escape * p
            probs.append(p)
        return probs

    def rank(self, candidates: Sequence[Option], time_of_day: str | None = None, at: float | None = None) -> list[Option]:
        return order_by_score(candidates, self.probabilities(candidates))


__all__ = ["LZ78", "ActiveLeZi"]
