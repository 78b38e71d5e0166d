"""Suggest SOMA/DUL classes for odb objects and tasks the mapping YAML does not cover (thesis 6.3.1).

A lexical and structural scorer with a small language model's word beside it: each candidate class of the upper ontology
(the descendants of dul:PhysicalObject for an object, of dul:Task for a task) is scored on
- its name and label against the entry's name (a compound written together, the head noun, shared
  words weighed by how rare they are among the classes' names),
- the same against the names of the entry's odb ancestors (``thermos`` derives from ``_bottle``),
- its rdfs:comment against the entry's words and the words of the tasks it affords (only the
  official SOMA files carry comments; the core TBox has none),
- the odb's structure: the class the entry already inherits from a mapped ancestor, and the
  classes of the mapped objects that afford the same tasks (its nearest neighbours by the SOMA
  tasks their odb tasks map to), with those classes' direct parents,
- how often the mapping already uses the class (a tie breaker),
- where the bundled language model is installed, how near it puts the entry's name to the
  class's name (oracle.ontology.suggest_embed).
Every part that adds to a score says so in the suggestion's ``why``.
"""

from __future__ import annotations

import math
import os
import re
from collections import Counter
from collections.abc import Iterable
from dataclasses import dataclass
from typing import TYPE_CHECKING

from oracle.namespaces import DUL_IRI
from oracle.ontology.mapping import Mapping
from oracle.ontology.odb import OdbObject, inherited_tasks
from oracle.ontology.suggest_embed import Nearness, class_text
from oracle.ontology.words import STOP_WORDS, joined, name_words, text_words

if TYPE_CHECKING:
    from rdflib import Graph

PHYSICAL_OBJECT = DUL_IRI + "PhysicalObject"
TASK = DUL_IRI + "Task"
#: Weights of the parts of a score (a name match is the strongest evidence a person would take).
W_NAME, W_ANCESTOR, W_COMMENT, W_INHERITED, W_NEIGHBOURS, W_PRIOR = 1.0, 0.5, 0.35, 0.45, 0.6, 0.08
#: The language model's probability for a class: a sure one weighs as much as a name match.
W_MODEL = 1.0
NEIGHBOURS = 5


@dataclass(frozen=True)
class UpperClass:
    """A class of the upper ontology as the scorer reads it."""

    iri: str
    local: str
    words: frozenset[str]
    first: str
    head: str
    joined: str
    comment: frozenset[str]
    parents: tuple[str, ...]


@dataclass(frozen=True)
class Suggestion:
    """One ranked class for an entry: higher scores are better; ``why`` is the evidence."""

    iri: str
    score: float
    why: str


def read_upper(graph: Graph) -> dict[str, UpperClass]:
    """Every named class of ``graph`` with its words, comment words and asserted named parents."""
    from rdflib import URIRef
    from rdflib.namespace import OWL, RDF, RDFS

    classes: dict[str, UpperClass] = {}
    for node in set(graph.subjects(RDF.type, OWL.Class)):
        if not isinstance(node, URIRef):
            continue
        iri = str(node)
        local = iri.rsplit("#", 1)[-1].rsplit("/", 1)[-1]
        own = name_words(local)
        if not own:
            continue
        labels = [w for label in graph.objects(node, RDFS.label) for w in name_words(str(label))]
        comment = [w for text in graph.objects(node, RDFS.comment) for w in text_words(str(text))]
        parents = tuple(sorted(str(p) for p in graph.objects(node, RDFS.subClassOf) if isinstance(p, URIRef)))
        classes[iri] = UpperClass(iri, local, frozenset(own) | frozenset(labels), own[0], own[-1], joined(local),
                                  frozenset(comment), parents)
    return classes


def descendants(classes: dict[str, UpperClass], root: str) -> set[str]:
    """``root`` and every class below it."""
    children: dict[str, list[str]] = {}
    for cls in classes.values():
        for parent in cls.parents:
            children.setdefault(parent, []).append(cls.iri)
    found = {root} if root in classes else set()
    stack = [root]
    while stack:
        for child in children.get(stack.pop(), ()):
            if child not in found:
                found.add(child)
                stack.append(child)
    return found


def guessed_objects(objects: dict[str, OdbObject], maps: Mapping) -> list[str]:
    """Objects with no line of their own nor of any odb ancestor: the build puts them under the
    mapping's ``root_object`` (directly or through unmapped parents), a guess."""
    out: list[str] = []
    for name in sorted(objects):
        seen: set[str] = set()
        queue = [name]
        mapped = False
        while queue and not mapped:
            current = queue.pop()
            if current in seen:
                continue
            seen.add(current)
            mapped = current in maps.object_map
            queue.extend(objects[current].parents)
        if not mapped:
            out.append(name)
    return out


class _Score:
    """The parts of one candidate's score and their reasons."""

    def __init__(self) -> None:
        self.total = 0.0
        self.reasons: list[tuple[float, str]] = []

    def add(self, weight: float, value: float, reason: str) -> None:
        if value > 0:
            self.total += weight * value
            self.reasons.append((weight * value, reason))

    def why(self) -> str:
        return "; ".join(r for _, r in sorted(self.reasons, key=lambda pair: -pair[0]))


class Suggester:
    """Ranks upper classes for the odb entries of one mapping (read once, asked many times)."""

    def __init__(self, objects: dict[str, OdbObject], maps: Mapping, classes: dict[str, UpperClass],
                 nearness: Nearness | None = None) -> None:
        self.objects = objects
        self.maps = maps
        self.classes = classes
        self.nearness = nearness
        self.object_pool = sorted(descendants(classes, PHYSICAL_OBJECT))
        self.task_pool = sorted(descendants(classes, TASK))
        self._idf = self._rarity(classes[i].words for i in self.object_pool + self.task_pool)
        self._comment_idf = self._rarity(classes[i].comment for i in self.object_pool + self.task_pool)
        self._children = self._odb_children()
        # generic roots (``_object``) are ancestors of most of the odb; their names say nothing
        counts = Counter(a for name in objects for a in self._ancestors(name))
        self._generic = {a for a, n in counts.items() if n > len(objects) / 2}
        self._signatures = {name: self._signature(name) for name in objects}
        self._task_idf = self._rarity(self._signatures.values())

    # -- public -------------------------------------------------------------------------------
    def uncovered_objects(self) -> list[str]:
        """Odb objects without their own line under ``soma_odb_map``."""
        return sorted(n for n in self.objects if n not in self.maps.object_map)

    def uncovered_tasks(self) -> list[str]:
        """Tasks an odb object names that have no entry under ``actions``."""
        return sorted({t for o in self.objects.values() for t in o.tasks} - set(self.maps.actions))

    def suggest_object(self, name: str, top: int = 5) -> list[Suggestion]:
        obj_words = self._entry_words(name)
        scores: dict[str, _Score] = {iri: _Score() for iri in self.object_pool}
        for iri, score in scores.items():
            value, reason = self._name_match(name, obj_words, self.classes[iri], head_last=True)
            score.add(W_NAME, value, reason)
            for ancestor, depth in self._named_ancestors(name):
                value, reason = self._name_match(ancestor, self._entry_words(ancestor), self.classes[iri], head_last=True)
                score.add(W_ANCESTOR / depth, value, f"odb parent {ancestor}: {reason}" if value else "")
        self._comment_evidence(scores, obj_words, self._task_words(name))
        inherited = self.inherited_class(name)
        if inherited is not None:
            source, cls = inherited
            for iri, score in scores.items():
                if iri == cls:
                    score.add(W_INHERITED, 1.0, f"inherited now from {source}")
                elif cls in self.classes[iri].parents:
                    score.add(W_INHERITED, 0.6, f"refines {self._curie(cls)}, inherited from {source}")
        self._neighbour_evidence(name, scores)
        self._model_evidence(name, self.object_pool, scores)
        self._prior(scores, exclude=name)
        return self._ranked(scores, top)

    def suggest_task(self, name: str, top: int = 5) -> list[Suggestion]:
        words = self._entry_words(name)
        scores: dict[str, _Score] = {iri: _Score() for iri in self.task_pool}
        for iri, score in scores.items():
            value, reason = self._name_match(name, words, self.classes[iri], head_last=False)
            score.add(W_NAME, value, reason)
        self._comment_evidence(scores, words, frozenset())
        # a task named after a mapped one (open_fridge after open) most likely shares its class
        for other, action in self.maps.actions.items():
            if other != name and name.startswith(other + "_") and action.task in scores:
                scores[action.task].add(W_INHERITED, 1.0, f"named after the mapped task {other}")
        self._model_evidence(name, self.task_pool, scores)
        counts = Counter(a.task for n, a in self.maps.actions.items() if n != name)
        self._add_prior(scores, counts)
        return self._ranked(scores, top)

    # -- evidence -----------------------------------------------------------------------------
    def _name_match(self, name: str, words: frozenset[str], cls: UpperClass, head_last: bool) -> tuple[float, str]:
        if joined(name) == cls.joined:
            return 1.0, f"name {name} = {cls.local}"
        parts = name_words(name)
        if not parts:
            return 0.0, ""
        head = parts[-1] if head_last else parts[0]
        cls_head = cls.head if head_last else cls.first
        shared = words & cls.words
        overlap = sum(self._idf.get(w, 1.0) for w in shared) / max(
            sum(self._idf.get(w, 1.0) for w in words | cls.words), 1e-9)
        if head == cls_head:
            return 0.6 + 0.4 * overlap, f"head word '{head}' of {name} heads {cls.local}"
        raw = [joined(w) for w in re.split(r"[_\-\s.]+", name) if joined(w)]
        if any("".join(raw[i:]) == cls.joined for i in range(1, len(raw))):
            return 0.8, f"{name} ends in the words of {cls.local}"
        if shared:
            return 0.6 * overlap, f"{name} shares {', '.join(sorted(shared))} with {cls.local}"
        # a word and its derivation share a long stem the inflection rules do not reach
        # (transfer / Transporting): five letters or more, most of the shorter word
        for word in words:
            for other in cls.words:
                common = len(os.path.commonprefix([word, other]))
                if common >= 5 and common >= 0.6 * min(len(word), len(other)):
                    return 0.35, f"{name}'s '{word}' and {cls.local}'s '{other}' share the stem '{word[:common]}'"
        return 0.0, ""

    def _comment_evidence(self, scores: dict[str, _Score], own: frozenset[str], tasks: frozenset[str]) -> None:
        if not own and not tasks:
            return
        total = sum(self._comment_idf.get(w, 1.0) for w in own) + 0.5 * sum(self._comment_idf.get(w, 1.0) for w in tasks)
        for iri, score in scores.items():
            # a comment that repeats the class's own name says nothing its name did not
            comment = self.classes[iri].comment - self.classes[iri].words
            hits_own, hits_task = own & comment, (tasks - own) & comment
            if not hits_own and not hits_task:
                continue
            value = (sum(self._comment_idf.get(w, 1.0) for w in hits_own)
                     + 0.5 * sum(self._comment_idf.get(w, 1.0) for w in hits_task)) / max(total, 1e-9)
            said = sorted(hits_own) + [f"{w} (a task)" for w in sorted(hits_task)]
            score.add(W_COMMENT, min(value, 1.0), f"its comment says {', '.join(said)}")

    def _neighbour_evidence(self, name: str, scores: dict[str, _Score]) -> None:
        mine = self._signatures[name]
        if not mine:
            return
        related = set(self._ancestors(name))
        near: list[tuple[float, str]] = []
        for other in self.maps.object_map:
            if other == name or other not in self._signatures or other in related:
                continue
            theirs = self._signatures[other]
            if theirs:
                # weighed by rarity: picking up says less than cutting about what a thing is
                similarity = (sum(self._task_idf[t] for t in mine & theirs)
                              / sum(self._task_idf[t] for t in mine | theirs)) ** 2
                if similarity > 0:
                    near.append((similarity, other))
        near.sort(key=lambda pair: (-pair[0], pair[1]))
        near = near[:NEIGHBOURS]
        weight = sum(s for s, _ in near)
        if not near:
            return
        votes: dict[str, float] = {}
        voters: dict[str, list[str]] = {}
        for similarity, other in near:
            cls = self.maps.object_map[other]
            for iri, share in [(cls, 1.0)] + [(p, 0.5) for p in self.classes[cls].parents if cls in self.classes]:
                votes[iri] = votes.get(iri, 0.0) + share * similarity / weight
                voters.setdefault(iri, []).append(other)
        for iri, vote in votes.items():
            if iri in scores:
                scores[iri].add(W_NEIGHBOURS, min(vote, 1.0), f"affords the tasks of {', '.join(voters[iri])}")

    def _model_evidence(self, name: str, pool: list[str], scores: dict[str, _Score]) -> None:
        if self.nearness is None:
            return
        texts = [class_text(self.classes[iri].local) for iri in pool]
        for iri, p in self.nearness.probabilities(name, pool, texts).items():
            if p >= 0.01:  # below one in a hundred it says nothing worth a line of why
                scores[iri].add(W_MODEL, p, f"the language model puts {name} near {self.classes[iri].local} ({p:.0%})")

    def _prior(self, scores: dict[str, _Score], exclude: str) -> None:
        self._add_prior(scores, Counter(c for o, c in self.maps.object_map.items() if o != exclude))
        root = self.maps.root_object
        if root in scores:
            scores[root].add(W_PRIOR, 0.5, "the mapping's root_object, where the build puts it now")

    @staticmethod
    def _add_prior(scores: dict[str, _Score], counts: Counter[str]) -> None:
        most = max(counts.values(), default=0)
        for iri, count in counts.items():
            if iri in scores and most:
                scores[iri].add(W_PRIOR, count / most, f"the mapping uses it {count} times")

    # -- the odb ------------------------------------------------------------------------------
    def _odb_children(self) -> dict[str, list[str]]:
        children: dict[str, list[str]] = {}
        for obj in self.objects.values():
            for parent in obj.parents:
                children.setdefault(parent, []).append(obj.name)
        return children

    def _ancestors(self, name: str) -> list[str]:
        found: list[str] = []
        queue = list(self.objects[name].parents)
        while queue:
            current = queue.pop(0)
            if current not in found:
                found.append(current)
                queue.extend(self.objects[current].parents)
        return found

    def _named_ancestors(self, name: str) -> list[tuple[str, int]]:
        """Ancestors whose names say something (not generic roots), with their distance."""
        out: list[tuple[str, int]] = []
        frontier, depth, seen = list(self.objects[name].parents), 1, set()
        while frontier:
            nxt: list[str] = []
            for a in frontier:
                if a in seen:
                    continue
                seen.add(a)
                if a not in self._generic:
                    out.append((a, depth))
                nxt.extend(self.objects[a].parents)
            frontier, depth = nxt, depth + 1
        return out

    def _descendants(self, name: str) -> list[str]:
        found: list[str] = []
        stack = list(self._children.get(name, ()))
        while stack:
            current = stack.pop()
            if current not in found:
                found.append(current)
                stack.extend(self._children.get(current, ()))
        return found

    def _tasks(self, name: str) -> set[str]:
        """What the entry affords: its own and inherited tasks, and, for an abstract entry, its
        descendants' (``_fruit`` affords what every fruit affords)."""
        tasks = set(inherited_tasks(self.objects, name))
        for child in self._descendants(name):
            tasks.update(self.objects[child].tasks)
        return tasks

    def _signature(self, name: str) -> frozenset[str]:
        """The SOMA tasks the entry's tasks map to (open_door and open both give soma:Opening)."""
        out = set()
        for task in self._tasks(name):
            action = self.maps.actions.get(task)
            out.add(action.task if action is not None and action.task != self.maps.defaults.task else "odb:" + task)
        return frozenset(out)

    def _task_words(self, name: str) -> frozenset[str]:
        return frozenset(w for t in self._tasks(name) for w in name_words(t) if w not in STOP_WORDS)

    def inherited_class(self, name: str) -> tuple[str, str] | None:
        """The nearest mapped odb ancestor of ``name`` and its class, if any."""
        for ancestor in self._ancestors(name):
            if ancestor in self.maps.object_map:
                return ancestor, self.maps.object_map[ancestor]
        return None

    @staticmethod
    def _entry_words(name: str) -> frozenset[str]:
        return frozenset(w for w in name_words(name) if w not in STOP_WORDS)

    @staticmethod
    def _rarity(groups: Iterable[frozenset[str]]) -> dict[str, float]:
        groups = list(groups)
        counts = Counter(w for g in groups for w in g)
        return {w: math.log(1 + len(groups) / n) for w, n in counts.items()}

    def _curie(self, iri: str) -> str:
        for prefix, ns in sorted(self.maps.prefixes.items(), key=lambda pair: -len(pair[1])):
            if iri.startswith(ns) and prefix != "odb":
                return f"{prefix}:{iri[len(ns):]}"
        return iri

    def _ranked(self, scores: dict[str, _Score], top: int) -> list[Suggestion]:
        ranked = sorted(((s.total, iri) for iri, s in scores.items() if s.total > 0), key=lambda pair: (-pair[0], pair[1]))
        return [Suggestion(iri, round(total, 4), scores[iri].why()) for total, iri in ranked[:top]]

    def curie(self, iri: str) -> str:
        """``soma:Cup`` for a SOMA IRI, the IRI itself where no prefix of the mapping fits."""
        return self._curie(iri)
