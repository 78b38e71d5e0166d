"""Values across the bridge: Python values as Prolog term text and pyswip terms, and back."""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from datetime import datetime
from typing import Any

from oracle.errors import PrologError


def plain(value: Any) -> Any:
    """A value pyswip handed to Python as the plain value the store expects."""
    from pyswip import Atom

    if isinstance(value, Atom):
        return value.value if isinstance(value.value, str) else value.value.decode("utf-8")
    if isinstance(value, bytes):
        return value.decode("utf-8")
    return value


def quote_atom(text: str) -> str:
    """``text`` as a quoted Prolog atom in pure ASCII (every other character escaped)."""
    if text.isascii() and text.isprintable():
        # The common case (IRIs), per value of every row a query returns: no loop in Python.
        return "'" + text.replace("\\", "\\\\").replace("'", "\\'") + "'"
    out = ["'"]
    for ch in text:
        code = ord(ch)
        if ch == "'" or ch == "\\":
            out.append("\\" + ch)
        elif 32 <= code < 127:
            out.append(ch)
        else:
            out.append(f"\\x{code:x}\\")
    out.append("'")
    return "".join(out)


def term_text(value: Any) -> str:
    """A store value as Prolog term text: IRIs and strings as atoms, numbers as numbers."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "1.5NaN"
        if math.isinf(value):
            return "1.0Inf" if value > 0 else "-1.0Inf"
        text = repr(value)
        if "e" in text and "." not in text.split("e")[0]:
            mantissa, exponent = text.split("e")
            text = f"{mantissa}.0e{exponent}"
        return text
    if isinstance(value, datetime):
        return term_text(value.timestamp())
    if isinstance(value, str):
        return quote_atom(value)
    if value is None:
        return quote_atom("")
    if hasattr(value, "to_decimal"):  # Decimal128 from a store that did not decode it
        return term_text(float(value.to_decimal()))
    return quote_atom(str(value))


def error_text(error: BaseException) -> str:
    """An error as the reply a foreign predicate hands to Prolog: ``error(Message)``."""
    return f"error({quote_atom(str(error) or type(error).__name__)})"



def json_value(text: str | bytes) -> Any:
    """The JSON text a Prolog goal bound (pyswip hands strings back as str or bytes), parsed."""
    return json.loads(text.decode("utf-8") if isinstance(text, bytes) else text)


def json_object(value: Any, what: str) -> dict[str, Any]:
    """``value`` when it is a JSON object, else a PrologError naming ``what`` gave it."""
    if not isinstance(value, dict):
        raise PrologError(f"{what} gave {type(value).__name__}, not a JSON object")
    return value


def atom(text: str) -> Any:
    """A Prolog atom for pyswip (its constructor is untyped; this is the one typed door)."""
    from pyswip import Atom

    make: Callable[[str], Any] = Atom
    return make(text)


def plain_term(value: Any) -> Any:
    """``Bridge.ask_plain``'s rule for one value."""
    if value is None:
        return atom("none")
    if isinstance(value, str):
        return atom(value)
    if isinstance(value, list):
        return [plain_term(v) for v in value]
    return value


class QueryValueError(PrologError):
    """A value a client bound in a query that Prolog cannot take."""


def term_value(name: str, value: Any) -> Any:
    if isinstance(value, bool) or value is None:
        raise QueryValueError(f"binding {name}: expected a string (atom) or a number, got {value!r}")
    if isinstance(value, (int, float)):
        return value
    if isinstance(value, str):
        return atom(value)
    if isinstance(value, list):
        return [term_value(name, v) for v in value]
    raise QueryValueError(f"binding {name}: expected a string (atom), a number or a list, got {type(value).__name__}")


def python_value(value: Any) -> Any:
    from pyswip import Atom

    if isinstance(value, Atom):
        return value.value
    if isinstance(value, bytes):
        return value.decode("utf-8")
    if isinstance(value, list):
        return [python_value(v) for v in value]
    return value
