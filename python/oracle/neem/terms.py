"""The SOMA/DUL terms a NEEM is written and read back with, as strings (store values are strings)."""

from __future__ import annotations

from oracle.namespaces import DUL, OWL, SOMA

NAMED_INDIVIDUAL = str(OWL.NamedIndividual)
ACTION = str(DUL.Action)
MENTAL_ACTION = str(SOMA.MentalAction)
EXECUTES = str(DUL.executesTask)
PARTICIPANT = str(DUL.hasParticipant)
PERFORMED_BY = str(SOMA.isPerformedBy)
HAS_INTERVAL = str(DUL.hasTimeInterval)
TIME_INTERVAL = str(DUL.TimeInterval)
BEGIN = str(SOMA.hasIntervalBegin)
END = str(SOMA.hasIntervalEnd)
IS_TASK_OF = str(DUL.isTaskOf)
CLASSIFIES = str(DUL.classifies)
PLAN = str(SOMA.ActionExecutionPlan)
PLAN_FOR = str(SOMA.isPlanFor)
IMAGINING = str(SOMA.Imagining)
REASONING = str(SOMA.Reasoning)
PREFERENCE_ORDER = str(SOMA.PreferenceOrder)
ORDER = str(SOMA.Order)
ORDERS = str(SOMA.orders)
ORDERED_ELEMENT = str(SOMA.OrderedElement)
ENCAPSULATES = str(SOMA.encapsulates)
ROBOT_CLASS = str(DUL.PhysicalAgent)
PERSON_CLASS = str(DUL.NaturalPerson)
