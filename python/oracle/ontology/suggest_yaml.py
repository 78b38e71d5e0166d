"""Suggestions as mapping YAML lines for a person to confirm, and ``--accept``: the top choices
added to the mapping file's own text (its comments and order kept), checked before it is written."""

from __future__ import annotations

import os
import re
import tempfile
from dataclasses import dataclass
from pathlib import Path

from oracle.errors import OntologyError
from oracle.ontology.mapping import load_mapping
from oracle.ontology.suggest import Suggester, Suggestion


@dataclass(frozen=True)
class Suggestions:
    """Ranked classes per entry the mapping lacks, objects and tasks apart."""

    objects: dict[str, list[Suggestion]]
    tasks: dict[str, list[Suggestion]]
    inherited: dict[str, str]  # object -> the class it inherits now from a mapped ancestor


def suggest_all(suggester: Suggester, top: int = 5) -> Suggestions:
    objects = {name: suggester.suggest_object(name, top) for name in suggester.uncovered_objects()}
    tasks = {name: suggester.suggest_task(name, top) for name in suggester.uncovered_tasks()}
    inherited = {}
    for name in objects:
        found = suggester.inherited_class(name)
        if found is not None:
            inherited[name] = found[1]
    return Suggestions(objects, tasks, inherited)


def yaml_lines(found: Suggestions, suggester: Suggester) -> list[str]:
    """The lines to paste into the mapping, each with its evidence and the runners-up as a comment."""
    lines: list[str] = []

    def comment(ranked: list[Suggestion]) -> str:
        best = ranked[0]
        others = ", ".join(f"{suggester.curie(s.iri)} {s.score:.2f}" for s in ranked[1:4])
        return f"# {best.score:.2f}: {best.why}" + (f" | then {others}" if others else "")

    if found.objects:
        lines.append("soma_odb_map:")
        # the objects that fall back to root_object first: they need a person most
        order = sorted(found.objects, key=lambda n: (n in found.inherited, n))
        for name in order:
            ranked = found.objects[name]
            if not ranked:
                lines.append(f"  # {name}: no evidence for any class (stays under root_object)")
                continue
            now = f" (inherits {suggester.curie(found.inherited[name])} now)" if name in found.inherited else ""
            lines.append(f"  {name}: {suggester.curie(ranked[0].iri)}    {comment(ranked)}{now}")
    if found.tasks:
        lines.append("actions:")
        for name, ranked in found.tasks.items():
            if not ranked:
                lines.append(f"  # {name}: no evidence for any task class (action_defaults stay)")
                continue
            lines.append(f"  {name}:")
            lines.append(f"    task: {suggester.curie(ranked[0].iri)}    {comment(ranked)}")
    return lines


def accepted(found: Suggestions, threshold: float) -> tuple[dict[str, str], dict[str, str]]:
    """The top choices at or above ``threshold``; an object whose top choice is the class it
    already inherits gets no line (it would change nothing)."""
    objects = {n: r[0].iri for n, r in found.objects.items()
               if r and r[0].score >= threshold and found.inherited.get(n) != r[0].iri}
    tasks = {n: r[0].iri for n, r in found.tasks.items() if r and r[0].score >= threshold}
    return objects, tasks


def _block_end(lines: list[str], key: str) -> int | None:
    """Index after the last indented line of the top-level block ``key:``; None if absent."""
    start = next((i for i, line in enumerate(lines) if re.match(rf"^{key}:\s*(#.*)?$", line)), None)
    if start is None:
        if any(line.startswith(f"{key}:") for line in lines):
            raise OntologyError(f"'{key}' is written inline; write it as a block to let --accept add lines")
        return None
    end = start + 1
    for i in range(start + 1, len(lines)):
        if lines[i].strip() == "" or lines[i].lstrip().startswith("#"):
            continue
        if not lines[i][0].isspace():
            break
        end = i + 1
    return end


def write_accepted(mapping: Path, objects: dict[str, str], tasks: dict[str, str], curie: dict[str, str]) -> None:
    """Add the lines to ``mapping``; the result must load as a mapping, or nothing is written."""
    lines = mapping.read_text(encoding="utf-8").splitlines()
    for key, new in (("soma_odb_map", [f"  {n}: {curie[c]}    # ontology suggest" for n, c in sorted(objects.items())]),
                     ("actions", [line for n, c in sorted(tasks.items())
                                  for line in (f"  {n}:    # ontology suggest", f"    task: {curie[c]}")])):
        if not new:
            continue
        end = _block_end(lines, key)
        if end is None:
            lines += [f"{key}:", *new]
        else:
            lines[end:end] = new
    text = "\n".join(lines) + "\n"
    fd, tmp = tempfile.mkstemp(dir=mapping.parent, prefix=".suggest-", suffix=".yaml")
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as out:
            out.write(text)
        try:
            load_mapping(tmp)  # the edited text must still be a valid mapping
        except OntologyError as error:
            raise OntologyError(f"{mapping}: not changed, the accepted lines would not load ({error})") from None
        os.replace(tmp, mapping)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
