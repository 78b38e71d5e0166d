"""Entities the odb ontology adds to SOMA (thesis 3.4), named in the odb namespace.

``IdleTask`` (robot in shared grasping for 20 s or more), ``imagines_situation`` (a mental action
imagining an available task as an ActionExecutionPlan), ``imagines_preference`` (a reasoning action
imagining a PreferenceOrder), ``TimeOfDay`` with its four parts, and the annotation and datatype
properties this project needs to keep task roles and preference ranks.
"""

from __future__ import annotations

from dataclasses import dataclass

from oracle.timeline import TIME_OF_DAY_NAMES


@dataclass(frozen=True)
class Vocabulary:
    namespace: str

    def term(self, local: str) -> str:
        return self.namespace + local

    @property
    def idle_task(self) -> str:
        return self.term("IdleTask")

    @property
    def imagines_situation(self) -> str:
        return self.term("imagines_situation")

    @property
    def imagines_preference(self) -> str:
        return self.term("imagines_preference")

    @property
    def time_of_day(self) -> str:
        return self.term("TimeOfDay")

    def part_of_day(self, name: str) -> str:
        if name not in TIME_OF_DAY_NAMES:
            raise ValueError(f"unknown part of day {name!r}; expected one of {', '.join(TIME_OF_DAY_NAMES)}")
        return self.term(name)

    @property
    def parts_of_day(self) -> tuple[str, ...]:
        return tuple(self.term(name) for name in TIME_OF_DAY_NAMES)

    # Preference elements carry their rank and score (SOMA has no numeric preference property).
    @property
    def has_rank(self) -> str:
        return self.term("hasPreferenceRank")

    @property
    def has_score(self) -> str:
        return self.term("hasPreferenceScore")

    # Annotation properties that keep the mapping's classification readable from the OWL file.
    @property
    def target_role(self) -> str:
        return self.term("targetRole")

    @property
    def reference_role(self) -> str:
        return self.term("referenceRole")

    @property
    def disposition(self) -> str:
        return self.term("disposition")

    @property
    def affords(self) -> str:
        return self.term("affords")

    @property
    def locals(self) -> frozenset[str]:
        """Local names of every entity introduced here (never odb objects or tasks)."""
        return frozenset(
            {"IdleTask", "imagines_situation", "imagines_preference", "TimeOfDay", *TIME_OF_DAY_NAMES,
             "hasPreferenceRank", "hasPreferenceScore", "targetRole", "referenceRole", "disposition", "affords"}
        )
