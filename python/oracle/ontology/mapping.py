"""The mapping YAML of thesis appendix A: how odb objects and tasks attach to SOMA/DUL.

Keys: ``namespace``, ``imports`` (prefix -> IRI), ``soma_odb_map`` (odb object -> class),
``root_object``, ``action_defaults`` and ``actions`` (task -> ``task``, ``ref_role``,
``target_role``, ``disposition``, ``parent``). A child action inherits every field it does not set
from its parent; an action without parent inherits from ``action_defaults``. ``False`` means
"no such role".
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any
from pathlib import Path

from oracle.errors import OntologyError
from oracle.namespaces import DEFAULT_ODB_NAMESPACE, STANDARD_PREFIXES
from oracle.yamlfile import check_keys, read_yaml

TOP_KEYS = frozenset({"namespace", "imports", "soma_odb_map", "root_object", "action_defaults", "actions"})
ACTION_FIELDS = ("task", "ref_role", "target_role", "disposition")
ACTION_KEYS = frozenset(ACTION_FIELDS) | {"parent"}


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
        return text
    if ":" not in text:
        raise OntologyError(f"{where}: {value!r} is not a prefixed name like soma:Cup")
    prefix, local = text.split(":", 1)
    if prefix not in prefixes:
        raise OntologyError(f"{where}: unknown prefix {prefix!r} in {value!r} (known: {', '.join(sorted(prefixes))})")
    if not local:
        raise OntologyError(f"{where}: {value!r} has an empty local name")
    return prefixes[prefix] + local


def _namespace(value: object, where: str) -> str:
    if value is None:
        return DEFAULT_ODB_NAMESPACE
    if not isinstance(value, str) or not value.startswith(("http://", "https://", "urn:")):
        raise OntologyError(f"{where}: 'namespace' must be an IRI, got {value!r}")
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
        if not isinstance(iri, str) or not iri.startswith(("http://", "https://", "urn:")):
            raise OntologyError(f"{path}: imports.{prefix}: {iri!r} is not an IRI")
        prefixes[str(prefix)] = iri
    prefixes["odb"] = namespace

    object_map: dict[str, str] = {}
    raw_map = data.get("soma_odb_map") or {}
    if not isinstance(raw_map, dict):
        raise OntologyError(f"{path}: 'soma_odb_map' must map odb objects to classes")
    for obj, cls in raw_map.items():
        if not isinstance(cls, str):
            raise OntologyError(f"{path}: soma_odb_map.{obj}: expected a class like soma:Cup, got {cls!r}")
        object_map[str(obj)] = expand_curie(cls, prefixes, f"{path}: soma_odb_map.{obj}")

    root_raw = data.get("root_object", "dul:PhysicalObject")
    if not isinstance(root_raw, str):
        raise OntologyError(f"{path}: 'root_object' must be a class like dul:PhysicalObject")
    root_object = expand_curie(root_raw, prefixes, f"{path}: root_object")

    defaults_raw = data.get("action_defaults") or {}
    _check_action_keys(defaults_raw, f"{path}: action_defaults", allow_parent=False)
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
        _check_action_keys(spec if spec is not None else {}, f"{path}: actions.{name}", allow_parent=True)
    actions = _resolve_actions(raw_actions, defaults, prefixes, path)
    return Mapping(namespace, prefixes, object_map, root_object, defaults, actions, path)


def _check_action_keys(spec: object, where: str, allow_parent: bool) -> None:
    if not isinstance(spec, dict):
        raise OntologyError(f"{where}: expected a mapping of {', '.join(ACTION_FIELDS)}")
    allowed = ACTION_KEYS if allow_parent else frozenset(ACTION_FIELDS)
    check_keys(spec, allowed, where, OntologyError)


def _resolve_actions(raw: dict, defaults: ActionMapping, prefixes: dict[str, str], path: Path) -> dict[str, ActionMapping]:
    resolved: dict[str, ActionMapping] = {}

    def resolve(name: str, stack: tuple[str, ...]) -> ActionMapping:
        if name in resolved:
            return resolved[name]
        if name in stack:
            raise OntologyError(f"{path}: actions: cyclic parent: {' -> '.join(stack + (name,))}")
        spec = raw[name] or {}
        parent_name = spec.get("parent")
        if parent_name is not None:
            parent_name = str(parent_name)
            if parent_name not in raw:
                raise OntologyError(f"{path}: actions.{name}: unknown parent {parent_name!r}")
            base = resolve(parent_name, stack + (name,))
        else:
            base = defaults
        where = f"{path}: actions.{name}"
        if "task" in spec and not isinstance(spec["task"], str):
            raise OntologyError(f"{where}.task: expected a task class like soma:Pouring")
        fields: dict[str, Any] = {
            "task": expand_curie(spec["task"], prefixes, f"{where}.task") if "task" in spec else base.task,
            "ref_role": _role(spec["ref_role"], prefixes, f"{where}.ref_role") if "ref_role" in spec else base.ref_role,
            "target_role": _role(spec["target_role"], prefixes, f"{where}.target_role") if "target_role" in spec else base.target_role,
            "disposition": _role(spec["disposition"], prefixes, f"{where}.disposition") if "disposition" in spec else base.disposition,
        }
        action = ActionMapping(
            name=name,
            parent=parent_name,
            explicit_task="task" in spec or parent_name is None,
            **fields,
        )
        resolved[name] = action
        return action

    for name in raw:
        resolve(str(name), ())
    return resolved
