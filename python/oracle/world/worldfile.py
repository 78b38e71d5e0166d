"""The kitchen world file (``ontology/kitchen-world.yaml``): reading and validating it into a
``rules.World``; every error is a WorldError naming the file and the entry."""

from __future__ import annotations

from typing import Any

import re
from collections.abc import Mapping
from pathlib import Path

from oracle.errors import WorldError
from oracle.paths import data_dir
from oracle.world.rules import EFFECTS, PREDICATES, Condition, TaskRule, World
from oracle.world.state import OBJECT_KINDS, ObjectSpec
from oracle.yamlfile import check_keys, read_yaml

_ATOM = re.compile(r"^\s*([a-z_]+)\s*(?:\(\s*([^()]*?)\s*\))?\s*$")
_TOP_KEYS = frozenset({"world", "park", "objects", "tasks"})
_OBJECT_KEYS = frozenset({"kind", "at", "affords", "tags", "accepts"})
_TASK_KEYS = frozenset({"args", "requires", "effects"})


def default_world() -> Path:
    """The world file of the sample kitchen (thesis Table 5.1) in the project's ``ontology/``."""
    return data_dir() / "kitchen-world.yaml"


def load_world(path: Path | str | None = None) -> World:
    """Read and validate a world file; every error names the file and the entry."""
    path = default_world() if path is None else Path(path)
    data = read_yaml(path, WorldError, "world file")
    if not isinstance(data, dict):
        raise WorldError(f"{path}: expected a mapping with keys objects, tasks, park")
    check_keys(data, _TOP_KEYS, str(path), WorldError)
    raw_tasks = data.get("tasks")
    raw_objects = data.get("objects")
    if not isinstance(raw_tasks, dict) or not raw_tasks:
        raise WorldError(f"{path}: 'tasks' must be a non-empty mapping")
    if not isinstance(raw_objects, dict) or not raw_objects:
        raise WorldError(f"{path}: 'objects' must be a non-empty mapping")
    objects = {str(name): _object(path, str(name), spec, raw_tasks) for name, spec in raw_objects.items()}
    _check_locations(path, objects)
    tags = frozenset().union(*(spec.tags for spec in objects.values()))
    tasks = {str(name): _task(path, str(name), spec, tags) for name, spec in raw_tasks.items()}
    park = data.get("park")
    if park not in objects or objects[park].kind != "surface":
        raise WorldError(f"{path}: park: {park!r} is not a surface of the world")
    return World(objects, tasks, park, path)


def _names(path: Path, where: str, value: object) -> tuple[str, ...]:
    if value is None:
        return ()
    if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
        raise WorldError(f"{path}: {where}: expected a list of names, got {value!r}")
    return tuple(value)


def _object(path: Path, name: str, spec: object, tasks: Mapping[str, Any]) -> ObjectSpec:
    where = f"objects.{name}"
    if not isinstance(spec, dict):
        raise WorldError(f"{path}: {where}: expected a mapping like {{at: counter_top, affords: [pick]}}")
    check_keys(spec, _OBJECT_KEYS, f"{path}: {where}", WorldError)
    kind = spec.get("kind", "item")
    if kind not in OBJECT_KINDS:
        raise WorldError(f"{path}: {where}.kind: {kind!r} is not one of {', '.join(OBJECT_KINDS)}")
    affords = _names(path, f"{where}.affords", spec.get("affords"))
    for task in affords:
        if task not in tasks:
            raise WorldError(f"{path}: {where}.affords: unknown task {task!r}")
    at = spec.get("at")
    if at is not None and not isinstance(at, str):
        raise WorldError(f"{path}: {where}.at: expected an object name, got {at!r}")
    if kind in ("surface", "container", "appliance") and at is not None:
        raise WorldError(f"{path}: {where}.at: a {kind} is a fixture and has no start location")
    if kind in ("item", "receptacle") and at is None:
        raise WorldError(f"{path}: {where}: a {kind} needs a start location 'at'")
    tags = frozenset(_names(path, f"{where}.tags", spec.get("tags")))
    accepts = frozenset(_names(path, f"{where}.accepts", spec.get("accepts")))
    return ObjectSpec(name, kind, at, affords, tags, accepts)


def _check_locations(path: Path, objects: Mapping[str, ObjectSpec]) -> None:
    for name, spec in objects.items():
        if spec.at is None:
            continue
        holder = objects.get(spec.at)
        if holder is None:
            raise WorldError(f"{path}: objects.{name}.at: unknown object {spec.at!r}")
        if holder.kind == "item" and not holder.accepts:
            raise WorldError(f"{path}: objects.{name}.at: {spec.at!r} is an item that holds nothing")
        seen = [name]
        current: str | None = spec.at
        while current is not None:
            if current in seen:
                raise WorldError(f"{path}: objects.{name}.at: locations form a cycle ({' -> '.join(seen + [current])})")
            seen.append(current)
            current = objects[current].at


def _atom(path: Path, where: str, text: object, table: Mapping[str, str], params: tuple[str, ...], tags: frozenset[str]) -> Condition:
    if not isinstance(text, str) or (match := _ATOM.match(text)) is None:
        raise WorldError(f"{path}: {where}: {text!r} is not an atom like holding(object)")
    name, inner = match.group(1), match.group(2)
    args = tuple(part.strip() for part in inner.split(",")) if inner else ()
    if name not in table:
        raise WorldError(f"{path}: {where}: unknown predicate {name!r}; known: {', '.join(table)}")
    signature = table[name]
    if len(args) != len(signature):
        raise WorldError(f"{path}: {where}: {name} takes {len(signature)} argument(s), got {text!r}")
    for arg, kind in zip(args, signature):
        if kind == "o" and arg not in params:
            raise WorldError(f"{path}: {where}: {arg!r} in {text!r} is not a parameter ({', '.join(params)})")
        if kind == "l" and arg not in tags:
            raise WorldError(f"{path}: {where}: no object has the tag {arg!r} used in {text!r}")
    return Condition(name, args, signature)


def _task(path: Path, name: str, spec: object, tags: frozenset[str]) -> TaskRule:
    where = f"tasks.{name}"
    if not isinstance(spec, dict):
        raise WorldError(f"{path}: {where}: expected a mapping with args, requires, effects")
    check_keys(spec, _TASK_KEYS, f"{path}: {where}", WorldError)
    params = _names(path, f"{where}.args", spec.get("args"))
    if not 1 <= len(params) <= 2 or len(set(params)) != len(params):
        raise WorldError(f"{path}: {where}.args: expected one or two distinct parameter names")
    requires = tuple(
        _atom(path, f"{where}.requires[{i}]", text, PREDICATES, params, tags)
        for i, text in enumerate(_list(path, f"{where}.requires", spec.get("requires")))
    )
    effects = tuple(
        _atom(path, f"{where}.effects[{i}]", text, EFFECTS, params, tags)
        for i, text in enumerate(_list(path, f"{where}.effects", spec.get("effects")))
    )
    return TaskRule(name, params, requires, effects)


def _list(path: Path, where: str, value: object) -> list[Any]:
    if value is None:
        return []
    if not isinstance(value, list):
        raise WorldError(f"{path}: {where}: expected a list, got {value!r}")
    return value
