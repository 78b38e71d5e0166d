"""What a request body would cost to parse, measured before anything parses it.

The guard refuses a body that nests too deep, holds too many values, carries a number or a
string too long, or is not UTF-8, so FastAPI's ``json.loads`` and pydantic (which run on the
event loop) only ever see bodies they get through in a few milliseconds. Every step here is a
C-speed pass over the body (two ``bytes.replace``, then numpy over slices), never a regex that
can backtrack: the old ``"(?:[^"\\\\]|\\\\.)*"`` pattern took 40 s for an 80 KB run of ``\\"``.
The numpy calls work on 256 KiB slices and each replace takes about a millisecond a MiB, so
no C call holds the GIL for long and the guard can run the whole measure in a worker thread
(guard.check_body) without stalling the loop (with ``serve --max-body`` far above 1 MiB the two
replaces grow with it).

For a body ``json.loads`` accepts (UTF-8), every figure is exact: the fuzz target
``tests/fuzz/targets.py::body_guard`` holds it equal to one worked out from what ``json.loads``
parsed. For any other body the figures are still computed in linear time, and the JSON parser
refuses the body later anyway.
"""

from __future__ import annotations

import json
from dataclasses import dataclass

import numpy as np

#: bytes -> +1 for an opening bracket, -1 for a closing one, 0 for anything else.
_STEP = np.zeros(256, dtype=np.int8)
_STEP[list(b"[{")] = 1
_STEP[list(b"]}")] = -1
#: Bytes a JSON number is made of (a run of them outside strings is one number literal).
_NUMBER = np.zeros(256, dtype=bool)
_NUMBER[list(b"0123456789+-.eE")] = True
#: Bytes that separate values and keys outside strings.
_SEPARATOR = np.zeros(256, dtype=bool)
_SEPARATOR[list(b",:")] = True
_QUOTE = ord('"')
#: Bytes per slice of the scan (about 0.1 ms of C per numpy call).
CHUNK = 1 << 18


@dataclass(frozen=True)
class Shape:
    """How a body is built: its nesting depth, how many values it holds, its longest number and
    string, and whether it is UTF-8."""

    depth: int
    values: int
    number_chars: int
    #: Longest string: the bytes between its quotes as sent, less its escaped quotes and
    #: backslashes (which count nothing).
    string_bytes: int = 0
    #: The body is UTF-8 (json.loads would read a UTF-16 or UTF-32 one too, where a quote or a
    #: bracket byte can be half of another character: the scan would not see what it parses).
    utf8: bool = True


def without_escapes(body: bytes) -> bytes:
    """The body with every backslash escape removed, in linear time: left to right, ``\\\\``
    pairs are exactly the escaped backslashes (a run of backslashes starts an escape, so the
    pairs line up), and the ``\\"`` left after them are exactly the escaped quotes. What remains
    has a quote only where a string opens or closes."""
    return body.replace(b"\\\\", b"").replace(b'\\"', b"")


def measure(body: bytes, chunk: int = CHUNK) -> Shape:
    """The shape of ``body`` (see the module docstring); linear in its size, in slices of
    ``chunk`` bytes so no single C call holds the GIL for long (any slice size gives the same
    shape: the fuzz target checks it)."""
    plain = without_escapes(body)
    scan = _Scan()
    for start in range(0, len(plain), chunk):
        scan.feed(np.frombuffer(plain, dtype=np.uint8, count=min(chunk, len(plain) - start), offset=start))
    root = 1 if body.strip(b" \t\r\n") else 0
    return Shape(scan.deepest, scan.values + root, scan.longest, scan.longest_string, _utf8(body))


def _utf8(body: bytes) -> bool:
    """Whether json.loads would read ``body`` as UTF-8 (it guesses from the first four bytes)."""
    return json.detect_encoding(body[:4]) in ("utf-8", "utf-8-sig")


class _Scan:
    """The running state of ``measure`` from one slice to the next."""

    def __init__(self) -> None:
        self.in_string = False
        self.depth = 0
        self.deepest = 0
        self.values = 0
        self.longest = 0
        self.open_run = 0
        self.longest_string = 0
        self.open_string = 0

    def feed(self, codes: np.ndarray) -> None:
        # np.equal, not ==: the fuzzer (atheris) traces every == and kept each array it saw
        quote = np.equal(codes, _QUOTE)
        # a byte lies in a string when an odd number of quotes precede it (its own included)
        parity = (np.cumsum(quote, dtype=np.int64) + self.in_string) & 1
        self.in_string = bool(parity[-1])
        outside = np.equal(parity, 0) & ~quote
        self.longest_string, self.open_string = _runs(np.equal(parity, 1) & ~quote, self.longest_string, self.open_string)
        bare = codes[outside]
        if bare.size == 0:
            return
        steps = _STEP[bare]
        running = np.cumsum(steps, dtype=np.int64) + self.depth
        self.deepest = max(self.deepest, int(running.max()))
        self.depth = int(running[-1])
        self.values += int(np.count_nonzero(np.equal(steps, 1))) + int(np.count_nonzero(_SEPARATOR[bare]))
        self.longest, self.open_run = _runs(_NUMBER[bare], self.longest, self.open_run)


def _runs(mask: np.ndarray, longest: int, carried: int) -> tuple[int, int]:
    """The longest run of True in ``mask`` (a run ``carried`` on from the slice before counted
    in) and the length of the run that reaches its end (0: none does)."""
    edges = np.diff(np.concatenate(([False], mask, [False])).astype(np.int8))
    lengths = np.flatnonzero(np.equal(edges, -1)) - np.flatnonzero(np.equal(edges, 1))
    if lengths.size == 0:
        return longest, 0
    if mask[0]:
        lengths[0] += carried
    return max(longest, int(lengths.max())), int(lengths[-1]) if mask[-1] else 0


def refusal(shape: Shape, depth: int, values: int, number_chars: int, string_bytes: int) -> str | None:
    """Why a body of this shape is refused (one line), or None when it may be parsed: deeper
    than ``depth``, more than ``values`` values, a number longer than ``number_chars``, a
    string longer than ``string_bytes``, or not UTF-8."""
    if not shape.utf8:
        return "the request body is not UTF-8 JSON"
    if shape.depth > depth:
        return f"the request body nests deeper than {depth} levels"
    if shape.values > values:
        return f"the request body holds more than {values} values"
    if shape.number_chars > number_chars:
        return f"the request body has a number longer than {number_chars} characters"
    if shape.string_bytes > string_bytes:
        return f"the request body has a string longer than {string_bytes} bytes"
    return None


__all__ = ["CHUNK", "Shape", "measure", "refusal", "without_escapes"]
