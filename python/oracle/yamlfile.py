"""Reading a YAML file so that every failure names the file (and line) in the caller's error type,
and checking a mapping's keys the same way."""

from __future__ import annotations

from collections.abc import Collection, Mapping
from pathlib import Path
from typing import Any

from oracle.errors import NeemOracleError
from oracle.handed import MAPPING_LIMIT, Handed, read_handed_text


def read_yaml(path: Path, error: type[NeemOracleError], what: str = "file", limit: int = MAPPING_LIMIT) -> Any:
    """Parsed content of ``path``; unreadable or malformed files raise ``error`` naming file and line.
    Only a regular file of at most ``limit`` bytes, in UTF-8, is read (oracle.handed)."""
    import yaml  # here, not at the top: a cached ontology build reads no YAML (~30 ms saved)

    text = read_handed_text(path, Handed(what, error), limit)
    try:
        return yaml.safe_load(text)
    except RecursionError:
        raise error(f"{path}: malformed YAML (nested too deeply)") from None
    except yaml.YAMLError as failure:
        mark = getattr(failure, "problem_mark", None)
        where = f"{path}:{mark.line + 1}" if mark is not None else str(path)
        raise error(f"{where}: malformed YAML ({getattr(failure, 'problem', failure)})") from None


def check_keys(data: Mapping[Any, Any], allowed: Collection[str], where: str, error: type[NeemOracleError]) -> None:
    """Raise ``error`` naming ``where``, the unknown keys and the allowed ones when ``data`` has others."""
    unknown = set(data) - set(allowed)
    if unknown:
        raise error(f"{where}: unknown key(s) {', '.join(sorted(map(str, unknown)))}; allowed: {', '.join(sorted(allowed))}")
