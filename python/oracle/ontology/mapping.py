"""The mapping YAML of thesis appendix A: how odb objects and tasks attach to SOMA/DUL.

Keys: ``namespace``, ``imports`` (prefix -> IRI), ``soma_odb_map`` (odb object -> class),
``root_object``, ``action_defaults`` and ``actions`` (task -> ``task``, ``ref_role``,
``target_role``, ``disposition``, ``parent``). A child action inherits every field it does not set
from its parent; an action without parent inherits from ``action_defaults``. ``False`` means
"no such role".
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any
from pathlib import Path

from oracle.errors import OntologyError
from oracle.namespaces import DEFAULT_ODB_NAMESPACE, STANDARD_PREFIXES
from oracle.yamlfile import check_keys, read_yaml

TOP_KEYS = frozenset({"namespace", "imports", "soma_odb_map", "root_object", "action_defaults", "actions"})
ACTION_FIELDS = ("task", "ref_role", "target_role", "disposition")
ACTION_KEYS = frozenset(ACTION_FIELDS) | {"parent"}
#: Task, object and prefix names: what odb manifests and the chain syntax can spell.
_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_\-]*$")
#: An absolute IRI as RDF/XML, Turtle and SPARQL can write it: a scheme we use, a host for
#: http(s), and none of the characters RFC 3987 excludes (spaces, quotes, angle brackets, ...).
_IRI = re.compile(r"^(?:https?://[^\s/?#<>\"{}|\\^`]+[^\s<>\"{}|\\^`]*|urn:[A-Za-z0-9][^\s<>\"{}|\\^`]*)$")


def check_iri(value: str, where: str) -> str:
    """``value`` if it is an absolute http(s) or urn IRI that every RDF syntax can write."""
    if not _IRI.match(value) or any(ord(c) < 0x20 for c in value):
        raise OntologyError(f"{where}: {value[:80]!r} is not a usable IRI (http://, https:// or urn:, no spaces or quotes)")
    return value


def _check_name(key: object, where: str, what: str) -> str:
    if not isinstance(key, str) or not _NAME.match(key):
        raise OntologyError(f"{where}: {key!r} is not a valid {what} (letters, digits, '_' and '-', not starting with a digit)")
    return key


@dataclass(frozen=True)
class ActionMapping:
    """A task's classification after inheritance; roles are IRIs or None."""

    name: str
    task: str
    ref_role: str | None
    target_role: str | None
    disposition: str | None
    parent: str | None
    explicit_task: bool


@dataclass(frozen=True)
class Mapping:
    namespace: str
    prefixes: dict[str, str]
    object_map: dict[str, str]
    root_object: str
    defaults: ActionMapping
    actions: dict[str, ActionMapping]
    source: Path

    def expand(self, curie: str) -> str:
        return expand_curie(curie, self.prefixes, str(self.source))


def expand_curie(value: str, prefixes: dict[str, str], where: str) -> str:
    """``soma:Cup`` -> full IRI; full IRIs pass through; unknown prefixes are an error."""
    text = value.strip().replace(" ", "")
    if text.startswith(("http://", "https://", "urn:")):
        return check_iri(text, where)
    if ":" not in text:
        raise OntologyError(f"{where}: {value!r} is not a prefixed name like soma:Cup")
    prefix, local = text.split(":", 1)
    if prefix not in prefixes:
        raise OntologyError(f"{where}: unknown prefix {prefix!r} in {value!r} (known: {', '.join(sorted(prefixes))})")
    if not local:
        raise OntologyError(f"{where}: {value!r} has an empty local name")
    return check_iri(prefixes[prefix] + local, where)


def _namespace(value: object, where: str) -> str:
    if value is None:
        return DEFAULT_ODB_NAMESPACE
    if not isinstance(value, str) or not value.startswith(("http://", "https://", "urn:")):
        raise OntologyError(f"{where}: 'namespace' must be an IRI, got {value!r}")
    check_iri(value, f"{where}: 'namespace'")
    return value if value.endswith(("#", "/")) else value + "#"


def _role(value: object, prefixes: dict[str, str], where: str) -> str | None:
    if value is False or value is None:
        return None
    if not isinstance(value, str):
        raise OntologyError(f"{where}: expected a class like soma:MovedObject or False, got {value!r}")
    return expand_curie(value, prefixes, where)


def load_mapping(path: Path | str) -> Mapping:
    """Read and validate a mapping YAML; every error names the file and the entry."""
    path = Path(path)
    data = read_yaml(path, OntologyError, "mapping")
    if not isinstance(data, dict):
        raise OntologyError(f"{path}: expected a mapping at the top level")
    check_keys(data, TOP_KEYS, str(path), OntologyError)
    where = str(path)
    namespace = _namespace(data.get("namespace"), where)
    prefixes = dict(STANDARD_PREFIXES)
    imports = data.get("imports") or {}
    if not isinstance(imports, dict):
        raise OntologyError(f"{path}: 'imports' must map prefixes to IRIs")
    for prefix, iri in imports.items():
        _check_name(prefix, f"{path}: imports", "prefix")
        if not isinstance(iri, str) or not iri.startswith(("http://", "https://", "urn:")):
            raise OntologyError(f"{path}: imports.{prefix}: {iri!r} is not an IRI")
        check_iri(iri, f"{path}: imports.{prefix}")
        prefixes[str(prefix)] = iri
    prefixes["odb"] = namespace

    object_map: dict[str, str] = {}
    raw_map = data.get("soma_odb_map") or {}
    if not isinstance(raw_map, dict):
        raise OntologyError(f"{path}: 'soma_odb_map' must map odb objects to classes")
    for obj, cls in raw_map.items():
        _check_name(obj, f"{path}: soma_odb_map", "odb object name")
        if not isinstance(cls, str):
            raise OntologyError(f"{path}: soma_odb_map.{obj}: expected a class like soma:Cup, got {cls!r}")
        object_map[str(obj)] = expand_curie(cls, prefixes, f"{path}: soma_odb_map.{obj}")

    root_raw = data.get("root_object", "dul:PhysicalObject")
    if not isinstance(root_raw, str):
        raise OntologyError(f"{path}: 'root_object' must be a class like dul:PhysicalObject")
    root_object = expand_curie(root_raw, prefixes, f"{path}: root_object")

    defaults_raw = data.get("action_defaults") or {}
    _check_action_keys(defaults_raw, f"{path}: action_defaults", allow_parent=False)
    if not isinstance(defaults_raw.get("task", ""), str):
        raise OntologyError(f"{path}: action_defaults.task: expected a task class like soma:PhysicalTask")
    defaults = ActionMapping(
        name="<defaults>",
        task=expand_curie(defaults_raw.get("task", "soma:PhysicalTask"), prefixes, f"{path}: action_defaults.task"),
        ref_role=_role(defaults_raw.get("ref_role", False), prefixes, f"{path}: action_defaults.ref_role"),
        target_role=_role(defaults_raw.get("target_role", "soma:Patient"), prefixes, f"{path}: action_defaults.target_role"),
        disposition=_role(defaults_raw.get("disposition", "soma:Disposition"), prefixes, f"{path}: action_defaults.disposition"),
        parent=None,
        explicit_task=True,
    )

    raw_actions = data.get("actions") or {}
    if not isinstance(raw_actions, dict):
        raise OntologyError(f"{path}: 'actions' must map task names to classifications")
    for name, spec in raw_actions.items():
        _check_name(name, f"{path}: actions.{name}", "task name")
        _check_action_keys(spec if spec is not None else {}, f"{path}: actions.{name}", allow_parent=True)
    actions = _resolve_actions(raw_actions, defaults, prefixes, path)
    return Mapping(namespace, prefixes, object_map, root_object, defaults, actions, path)


def _check_action_keys(spec: object, where: str, allow_parent: bool) -> None:
    if not isinstance(spec, dict):
        raise OntologyError(f"{where}: expected a mapping of {', '.join(ACTION_FIELDS)}")
    allowed = ACTION_KEYS if allow_parent else frozenset(ACTION_FIELDS)
    check_keys(spec, allowed, where, OntologyError)


def _resolve_actions(raw: dict[str, Any], defaults: ActionMapping, prefixes: dict[str, str], path: Path) -> dict[str, ActionMapping]:
    resolved: dict[str, ActionMapping] = {}

    def chain(name: str) -> list[str]:
        """``name`` and its ancestors up to the first one already resolved or without parent,
        found in a loop rather than by recursion (a parent chain may be thousands deep)."""
        found = [name]
        while name not in resolved:
            parent_name = (raw[name] or {}).get("parent")
            if parent_name is None:
                break
            if not isinstance(parent_name, str) or parent_name not in raw:
                raise OntologyError(f"{path}: actions.{name}: unknown parent {parent_name!r}")
            if parent_name in found:
                cycle = found[found.index(parent_name):] + [parent_name]
                raise OntologyError(f"{path}: actions: cyclic parent: {' -> '.join(cycle)}")
            found.append(parent_name)
            name = parent_name
        return found

    def resolve_one(name: str) -> ActionMapping:
        spec = raw[name] or {}
        parent_name = spec.get("parent")
        base = resolved[parent_name] if parent_name is not None else defaults
        where = f"{path}: actions.{name}"
        if "task" in spec and not isinstance(spec["task"], str):
            raise OntologyError(f"{where}.task: expected a task class like soma:Pouring")
        fields: dict[str, Any] = {
            "task": expand_curie(spec["task"], prefixes, f"{where}.task") if "task" in spec else base.task,
            "ref_role": _role(spec["ref_role"], prefixes, f"{where}.ref_role") if "ref_role" in spec else base.ref_role,
            "target_role": _role(spec["target_role"], prefixes, f"{where}.target_role") if "target_role" in spec else base.target_role,
            "disposition": _role(spec["disposition"], prefixes, f"{where}.disposition") if "disposition" in spec else base.disposition,
        }
        return ActionMapping(name=name, parent=parent_name, explicit_task="task" in spec or parent_name is None, **fields)

    for name in raw:
        for member in reversed(chain(name)):
            if member not in resolved:
                resolved[member] = resolve_one(member)
    return resolved
