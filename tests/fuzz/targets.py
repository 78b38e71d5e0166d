"""Fuzz targets: each takes the fuzzer's bytes and raises on a bug (an exception the code under
test must never raise, or an answer that disagrees with an independent reference).

``TARGETS`` maps a name to its function; ``harness.py`` runs any of them under atheris and
``test_fuzz.py`` replays every input saved under ``regressions/<name>/``. A new parser joins by
adding its function here.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from typing import Any

from oracle.service import bodyshape
from oracle.service.guard import Guard, Limits, allowed_hosts


class _Pairs(list[tuple[str, Any]]):
    """An object as json.loads read it (its key/value pairs, duplicates kept)."""


def reference_shape(body: bytes) -> bodyshape.Shape | None:
    """The shape of a body ``json.loads`` accepts, worked out from what it parsed (depth, values,
    number literals) and a byte-by-byte scan (strings); None for a body it refuses."""
    numbers = [0]

    def number(text: str) -> float:
        numbers[0] = max(numbers[0], len(text))
        return 0.0

    try:
        parsed = json.loads(body, object_pairs_hook=_Pairs, parse_int=number, parse_float=number,
                            parse_constant=lambda text: number("-") if text.startswith("-") else 0.0)
    except (ValueError, RecursionError):
        return None
    depth, values = _tree(parsed)
    bare = _strings_and_rest(body)
    if bare is None:
        return None
    rest, longest_string = bare
    # "true" and "false" hold an "e", a number byte; it stands alone between letters
    letters = 1 if (b"true" in rest or b"false" in rest) else 0
    return bodyshape.Shape(depth, values, max(numbers[0], letters), longest_string)


def _tree(node: Any) -> tuple[int, int]:
    """(depth, values + keys + empty containers) of a parsed tree: what the separator count of
    bodyshape gives for valid JSON."""
    if isinstance(node, _Pairs):
        children = [value for _, value in node]
        keys = len(node)
    elif isinstance(node, list):
        children, keys = node, 0
    else:
        return 0, 1
    depth, values = 0, 1 + keys + (0 if children else 1)
    for child in children:
        d, v = _tree(child)
        depth, values = max(depth, d), values + v
    return depth + 1, values


def _strings_and_rest(body: bytes) -> tuple[bytes, int] | None:
    """The bytes outside strings and the longest string's length as bodyshape counts it, by
    walking the body one byte at a time."""
    rest = bytearray()
    longest = length = 0
    inside = escaped = False
    for byte in body:
        if not inside:
            if byte == 0x22:
                inside, length = True, 0
            else:
                rest.append(byte)
        elif escaped:
            escaped = False
            length += 0 if byte in b'"\\' else 2
        elif byte == 0x5C:
            escaped = True
        elif byte == 0x22:
            inside = False
            longest = max(longest, length)
        else:
            length += 1
    return None if inside else (bytes(rest), longest)


#: Pieces a generated JSON text is made of: escapes, quotes and brackets are what the scan
#: must not confuse.
_STRING_PIECES = (b"a", b"\\\\", b'\\"', b"\\n", b"\\u00e9", b"\\ud83d\\ude00", b"[", b"]", b"{", b"}", b",", b":",
                  "é".encode(), b"\\/", b" ")
_SPACE = (b"", b" ", b"\n", b"\t ", b"\r\n")
_LITERALS = (b"true", b"false", b"null", b"0", b"-1", b"3.25e-7", b"1E+400", b"NaN", b"-Infinity", b"123456789012")


def json_text(data: bytes) -> bytes:
    """A JSON text built from the fuzzer's bytes (valid by construction but for the byte that
    asks for a mutation), so the comparison with the reference runs on most inputs."""
    out = bytearray()
    at = [0]

    def take(n: int) -> int:
        if at[0] >= len(data):
            return 0
        at[0] += 1
        return data[at[0] - 1] % n

    def value(depth: int) -> None:
        out.extend(_SPACE[take(len(_SPACE))])
        kind = take(6) if depth < 40 else 0
        if kind == 0:
            out.extend(_LITERALS[take(len(_LITERALS))])
        elif kind == 1:
            out.extend(b'"' + b"".join(_STRING_PIECES[take(len(_STRING_PIECES))] for _ in range(take(8))) + b'"')
        elif kind in (2, 3):
            out.extend(b"[")
            for i in range(take(5)):
                out.extend(b"," if i else b"")
                value(depth + 1)
            out.extend(b"]")
        else:
            out.extend(b"{")
            for i in range(take(4)):
                out.extend(b"," if i else b"")
                out.extend(b'"' + b"".join(_STRING_PIECES[take(len(_STRING_PIECES))] for _ in range(take(4))) + b'":')
                value(depth + 1)
            out.extend(b"}")
        out.extend(_SPACE[take(len(_SPACE))])

    value(0)
    if take(8) == 0 and out:  # now and then one byte changed: near-JSON, the parser's edge
        out[take(len(out))] = take(256)
    return bytes(out)


def body_guard(data: bytes) -> None:
    """bodyshape.measure never raises, gives the same shape whatever its slice size, and for
    every body json.loads accepts gives exactly the reference shape; the guard's refusal
    follows from the shape alone. The first byte picks the slice size and whether the rest is
    the body itself or the recipe of a generated JSON text (json_text)."""
    if not data:
        return
    chunk = 1 + data[0] % 64
    body = data[1:] if data[0] & 64 else json_text(data[1:])
    shape = bodyshape.measure(body)
    assert shape == bodyshape.measure(body, chunk=chunk), (shape, chunk)
    assert min(shape.depth, shape.values, shape.number_chars, shape.string_bytes) >= 0, shape
    expected = reference_shape(body) if shape.utf8 else None
    if expected is not None:
        assert shape == expected, (shape, expected)
    reason = bodyshape.refusal(shape, 3, 20, 5, 10)
    assert (reason is None) == (shape.utf8 and shape.depth <= 3 and shape.values <= 20 and shape.number_chars <= 5
                                and shape.string_bytes <= 10), (shape, reason)


def guard_read(data: bytes) -> None:
    """The guard's whole body path (guard.Guard on a stub app): any body, cut in any pieces,
    with a true, false or no Content-Length, is answered 200 (the app saw exactly that body),
    400, 413 or 503, never raises, and leaves no body bytes counted as held."""
    import asyncio
    from types import SimpleNamespace


    if len(data) < 2:
        return
    limits = Limits(body_bytes=64, json_depth=3, json_values=20, number_chars=5, string_bytes=10, buffered_bytes=48,
                    small_body=16)
    ctx = SimpleNamespace(limits=limits, allowed_hosts=allowed_hosts("127.0.0.1"), token=None)
    cut, length, body = data[0], data[1], data[2:]
    seen: list[bytes] = []

    async def app(scope: Any, receive: Any, send: Any) -> None:
        message = await receive()
        seen.append(message["body"])
        await send({"type": "http.response.start", "status": 200, "headers": []})
        await send({"type": "http.response.body", "body": b""})

    step = 1 + cut % 64
    pieces = [body[i:i + step] for i in range(0, len(body), step)] or [b""]
    messages = [{"type": "http.request", "body": p, "more_body": k < len(pieces) - 1} for k, p in enumerate(pieces)]
    headers = [(b"host", b"127.0.0.1")]
    if length % 3 == 0:
        headers.append((b"content-length", str(len(body)).encode()))
    elif length % 3 == 1:
        headers.append((b"content-length", str(length).encode()))
    statuses: list[int] = []

    async def receive() -> dict[str, Any]:
        return messages.pop(0) if messages else {"type": "http.disconnect"}

    async def send(message: dict[str, Any]) -> None:
        if message["type"] == "http.response.start":
            statuses.append(message["status"])

    guard = Guard(app, ctx)
    path = "/api/neems/ada/situation" if cut & 128 else "/api/prolog"  # a robot route or not
    scope = {"type": "http", "method": "POST", "path": path, "headers": headers, "query_string": b""}
    asyncio.run(guard(scope, receive, send))
    assert statuses and statuses[0] in (200, 400, 413, 503), statuses
    assert guard.budget.held == 0 and guard.in_flight == 0 and guard.robots.running == 0, vars(guard)
    if statuses[0] == 200:
        assert seen == [body], (seen, body)


TARGETS: dict[str, Callable[[bytes], None]] = {"body_guard": body_guard, "guard_read": guard_read}
