"""A fitted model as plain data: JSON for its structure, raw bytes for its numpy arrays.

This replaces pickle wherever a model is kept (oracle.fitcache): reading an entry can only make
builtin containers and numbers, numpy arrays of numeric dtypes, and instances of the classes a
caller names in ``allowed`` (looked up by their exact ``module:qualname``, never resolved as a
dotted path), filled with their own ``__setstate__`` or their ``__dict__``. Nothing in the bytes
names a function to call, so a hostile entry can fail to decode (``PlainStateError``) but can run
nothing. A class with ``plain_state()`` and the class method ``from_plain_state(state)`` is
kept as the state it gives (a compact one, such as a few flat arrays). One object given as
``shared`` (the caller's distance matrix) is written as a reference and put back on reading.

Layout: ``MAGIC``, the JSON text's length (8 bytes, little-endian), the JSON text, then the
arrays' bytes, each at an offset the JSON gives. Every object that pickle would memoise (containers,
instances, arrays) is numbered in the order it is first met, and a second meeting writes
``["r", n]``, so shared references stay shared, as they do through pickle.
"""

from __future__ import annotations

import base64
import json
import re
from collections import Counter, OrderedDict, defaultdict, deque
from collections.abc import Callable, Iterable, Mapping
from typing import Any

import numpy as np

MAGIC = b"neem-oracle plain 1\n"
#: numpy dtypes an entry may hold: booleans, integers, floats, complex; one byte order mark.
_DTYPE = re.compile(r"[<>|=]?[?biufc][0-9]{0,2}")
#: What a defaultdict may make for a missing key (the only callables an entry can name).
_FACTORIES: dict[str, Callable[[], Any]] = {"int": int, "float": float, "list": list, "dict": dict, "set": set}
_ALIGN = 16


class PlainStateError(ValueError):
    """The bytes are not a model this module wrote (damaged, foreign or hostile)."""


def class_name(cls: type) -> str:
    return f"{cls.__module__}:{cls.__qualname__}"


def classes_of(modules: Iterable[Any]) -> dict[str, type]:
    """The classes defined in ``modules`` (not imported into them), by ``class_name``."""
    found: dict[str, type] = {}
    for module in modules:
        for value in vars(module).values():
            if isinstance(value, type) and value.__module__ == module.__name__:
                found[class_name(value)] = value
    return found


def dumps(obj: Any, allowed: Mapping[str, type], shared: Any = None) -> bytes:
    """``obj`` as plain bytes; PlainStateError when it holds something this format cannot keep
    (a class not in ``allowed``, a function, an array of objects)."""
    writer = _Writer(allowed, shared)
    tree = writer.node(obj)
    text = json.dumps(tree, separators=(",", ":"), allow_nan=True).encode()
    return b"".join([MAGIC, len(text).to_bytes(8, "little"), text, *writer.blobs])


def loads(data: bytes, allowed: Mapping[str, type], shared: Any = None) -> Any:
    """The object ``dumps`` wrote into ``data``; PlainStateError for anything else."""
    view = memoryview(data)
    if bytes(view[:len(MAGIC)]) != MAGIC or len(view) < len(MAGIC) + 8:
        raise PlainStateError("not a plain model")
    size = int.from_bytes(view[len(MAGIC):len(MAGIC) + 8], "little")
    start = len(MAGIC) + 8
    if size > len(view) - start:
        raise PlainStateError("its structure runs past its end")
    try:
        tree = json.loads(bytes(view[start:start + size]))
    except (ValueError, RecursionError) as error:
        raise PlainStateError(f"its structure is not JSON: {error}") from None
    # one writable buffer for every array (a model grows its arrays in place)
    reader = _Reader(allowed, shared, bytearray(view[start + size:]))
    try:
        return reader.node(tree)
    except PlainStateError:
        raise
    except (TypeError, ValueError, KeyError, IndexError, AttributeError, RecursionError, OverflowError) as error:
        raise PlainStateError(f"its structure does not make a model: {type(error).__name__}") from None


class _Writer:
    def __init__(self, allowed: Mapping[str, type], shared: Any) -> None:
        self.allowed = allowed
        self.shared = shared
        self.memo: dict[int, int] = {}
        self.alive: list[Any] = []  # keeps every numbered object (and its id) alive while writing
        self.blobs: list[bytes] = []
        self.offset = 0

    def _number(self, obj: Any) -> None:
        self.memo[id(obj)] = len(self.alive)
        self.alive.append(obj)

    def node(self, obj: Any) -> Any:
        if type(obj) in _PLAIN:
            return obj
        if self.shared is not None and obj is self.shared:
            return ["S"]
        seen = self.memo.get(id(obj))
        if seen is not None:
            return ["r", seen]
        kind = type(obj)
        if kind is bytes:
            return ["B", base64.b64encode(obj).decode()]
        if isinstance(obj, np.generic):
            return self._scalar(obj)
        self._number(obj)
        if kind is np.ndarray:
            return self._array(obj)
        node = self.node
        if kind in _SEQUENCES:
            return [_SEQUENCES[kind], [item if type(item) in _PLAIN else node(item) for item in obj]]
        if kind in _MAPPINGS or kind is defaultdict:
            # keys first, then values (the order the reader makes them in)
            keys = [key if type(key) in _PLAIN else node(key) for key in obj]
            values = [value if type(value) in _PLAIN else node(value) for value in obj.values()]
            if kind is not defaultdict:
                return [_MAPPINGS[kind], keys, values]
            factory = next((name for name, made in _FACTORIES.items() if obj.default_factory is made), None)
            if factory is None:
                raise PlainStateError(f"a defaultdict making {obj.default_factory!r}")
            return ["dd", factory, keys, values]
        return self._instance(obj)

    def _scalar(self, value: np.generic) -> Any:
        dtype = value.dtype.str
        if not _DTYPE.fullmatch(dtype):
            raise PlainStateError(f"a numpy scalar of dtype {dtype}")
        return ["n", dtype, self.node(value.item())]

    def _array(self, array: np.ndarray[Any, Any]) -> Any:
        dtype = array.dtype.str
        if not _DTYPE.fullmatch(dtype):
            raise PlainStateError(f"an array of dtype {dtype}")
        raw = np.ascontiguousarray(array).tobytes()
        pad = -len(raw) % _ALIGN
        self.blobs.append(raw + bytes(pad))
        at = self.offset
        self.offset += len(raw) + pad
        return ["a", dtype, list(array.shape), at, len(raw)]

    def _instance(self, obj: Any) -> Any:
        name = class_name(type(obj))
        if self.allowed.get(name) is not type(obj):
            raise PlainStateError(f"an instance of {name}, which a kept model may not hold")
        compact = getattr(obj, "plain_state", None)
        if callable(compact):
            return ["p", name, self.node(compact())]
        reduced = obj.__reduce_ex__(5)
        if not isinstance(reduced, tuple) or getattr(reduced[0], "__name__", "") != "__newobj__" \
                or reduced[1][0] is not type(obj) or len(reduced) > 3 and (reduced[3] is not None or reduced[4] is not None):
            raise PlainStateError(f"{name} does not reduce to its class and its state")
        args = [self.node(arg) for arg in reduced[1][1:]]
        state = reduced[2] if len(reduced) > 2 else None
        return ["o", name, args, self.node(state)]


#: What JSON holds as it is (NaN and infinities too: json writes and reads them).
_PLAIN = frozenset({int, float, str, bool, type(None)})
_SEQUENCES: dict[type, str] = {list: "l", tuple: "t", set: "s", frozenset: "f", deque: "q"}
_MAPPINGS: dict[type, str] = {dict: "d", OrderedDict: "od", Counter: "c"}


class _Reader:
    def __init__(self, allowed: Mapping[str, type], shared: Any, arrays: bytearray) -> None:
        self.allowed = allowed
        self.shared = shared
        self.arrays = arrays
        self.memo: list[Any] = []

    def node(self, tree: Any) -> Any:
        if tree is None or isinstance(tree, (bool, int, float, str)):
            return tree
        if not isinstance(tree, list) or not tree or not isinstance(tree[0], str):
            raise PlainStateError("an unknown node")
        tag = tree[0]
        if tag == "S":
            if self.shared is None:
                raise PlainStateError("a shared reference with nothing shared")
            return self.shared
        if tag == "r":
            slot = tree[1]
            if type(slot) is not int or not 0 <= slot < len(self.memo) or self.memo[slot] is _PENDING:
                raise PlainStateError("a reference to nothing made yet")
            return self.memo[slot]
        if tag == "B":
            return base64.b64decode(tree[1], validate=True)
        if tag == "n":
            value = tree[2]
            if not isinstance(value, (bool, int, float)):
                raise PlainStateError("a numpy scalar that is not a number")
            return _numpy_type(tree[1])(value)
        slot = len(self.memo)
        self.memo.append(_PENDING)
        made = self._made(tag, tree, slot)
        self.memo[slot] = made
        return made

    def _made(self, tag: str, tree: list[Any], slot: int) -> Any:
        if tag == "a":
            return self._array(tree)
        node = self.node
        if tag in ("l", "q"):
            made: Any = [] if tag == "l" else deque()
            self.memo[slot] = made  # an object inside may refer back to its container
            made.extend([item if type(item) is not list else node(item) for item in _listed(tree[1])])
            return made
        if tag in ("t", "f", "s"):
            items = [item if type(item) is not list else node(item) for item in _listed(tree[1])]
            return {"t": tuple, "f": frozenset, "s": set}[tag](items)
        if tag in ("d", "od", "c", "dd"):
            mapping: dict[Any, Any] = (defaultdict(_FACTORIES[tree[1]]) if tag == "dd"
                                       else {"d": dict, "od": OrderedDict, "c": Counter}[tag]())
            self.memo[slot] = mapping
            keys = [key if type(key) is not list else node(key) for key in _listed(tree[-2])]
            values = [value if type(value) is not list else node(value) for value in _listed(tree[-1])]
            if len(keys) != len(values):
                raise PlainStateError("a mapping whose keys and values differ in number")
            mapping.update(zip(keys, values))
            return mapping
        if tag == "o":
            return self._instance(tree, slot)
        if tag == "p":
            cls = self._class(tree[1])
            return cls.from_plain_state(self.node(tree[2]))  # type: ignore[attr-defined]
        raise PlainStateError(f"an unknown node {tag!r}")

    def _class(self, name: Any) -> type:
        cls = self.allowed.get(name) if isinstance(name, str) else None
        if cls is None:
            raise PlainStateError(f"an instance of {name!r}, which a kept model may not hold")
        return cls

    def _array(self, tree: list[Any]) -> np.ndarray[Any, Any]:
        _, dtype, shape, at, size = tree
        kind = _numpy_dtype(dtype)
        if not (isinstance(shape, list) and all(type(n) is int and n >= 0 for n in shape)
                and type(at) is int and type(size) is int and 0 <= at and at + size <= len(self.arrays)):
            raise PlainStateError("an array outside its bytes")
        if int(np.prod(shape, dtype=np.int64)) * kind.itemsize != size:
            raise PlainStateError("an array whose shape does not fit its bytes")
        buffer = memoryview(self.arrays)[at:at + size]
        return np.frombuffer(buffer, dtype=kind).reshape(shape)

    def _instance(self, tree: list[Any], slot: int) -> Any:
        _, name, args, state = tree
        cls = self._class(name)
        made = cls.__new__(cls, *[self.node(arg) for arg in _listed(args)])
        self.memo[slot] = made
        value = self.node(state)
        if value is None:
            return made
        setstate = getattr(made, "__setstate__", None)
        if setstate is not None:
            setstate(value)
        elif isinstance(value, dict):
            made.__dict__.update(value)
        elif isinstance(value, tuple) and len(value) == 2:
            if value[0]:
                made.__dict__.update(value[0])
            for key, item in value[1].items():
                object.__setattr__(made, key, item)
        else:
            raise PlainStateError(f"a state of {name} that is not one")
        return made


_PENDING = object()


def _listed(value: Any) -> list[Any]:
    if not isinstance(value, list):
        raise PlainStateError("a list expected")
    return value


def _numpy_dtype(text: Any) -> np.dtype[Any]:
    if not isinstance(text, str) or not _DTYPE.fullmatch(text):
        raise PlainStateError(f"a dtype this format does not hold: {text!r}")
    return np.dtype(text)


def _numpy_type(text: Any) -> Callable[[Any], Any]:
    return _numpy_dtype(text).type
