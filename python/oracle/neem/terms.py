"""The SOMA/DUL terms a NEEM is written and read back with, as strings (store values are
strings; built from the namespace IRIs, so reading a NEEM needs no rdflib)."""

from __future__ import annotations

from oracle.namespaces import DUL_IRI as DUL, OWL_IRI as OWL, SOMA_IRI as SOMA

NAMED_INDIVIDUAL = OWL + "NamedIndividual"
ACTION = DUL + "Action"
MENTAL_ACTION = SOMA + "MentalAction"
EXECUTES = DUL + "executesTask"
PARTICIPANT = DUL + "hasParticipant"
PERFORMED_BY = SOMA + "isPerformedBy"
HAS_INTERVAL = DUL + "hasTimeInterval"
TIME_INTERVAL = DUL + "TimeInterval"
BEGIN = SOMA + "hasIntervalBegin"
END = SOMA + "hasIntervalEnd"
IS_TASK_OF = DUL + "isTaskOf"
CLASSIFIES = DUL + "classifies"
PLAN = SOMA + "ActionExecutionPlan"
PLAN_FOR = SOMA + "isPlanFor"
IMAGINING = SOMA + "Imagining"
REASONING = SOMA + "Reasoning"
PREFERENCE_ORDER = SOMA + "PreferenceOrder"
ORDER = SOMA + "Order"
ORDERS = SOMA + "orders"
ORDERED_ELEMENT = SOMA + "OrderedElement"
ENCAPSULATES = SOMA + "encapsulates"
ROBOT_CLASS = DUL + "PhysicalAgent"
PERSON_CLASS = DUL + "NaturalPerson"
