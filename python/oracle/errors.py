"""Errors a user can cause. Each domain has one type; the CLI prints them as one line."""

from __future__ import annotations


class NeemOracleError(Exception):
    """Base of every error caused by bad input rather than by a bug."""


class OntologyError(NeemOracleError):
    """A malformed odb, mapping or ontology file; the message names the file and entry."""


class WorldError(NeemOracleError):
    """A malformed kitchen world file (objects, tasks, rules); the message names the file and entry."""


class StoreError(NeemOracleError):
    """A NEEM store cannot be opened, read or written as asked."""


class CorruptStoreError(StoreError):
    """The store's file is damaged: nothing may be written into it (oracle.store.integrity). Never
    softened into a note: a command that meets it fails."""


class ChainSyntaxError(NeemOracleError):
    """An action string such as ``pour(thermos, green_mug)`` is malformed."""


class LoggingError(NeemOracleError):
    """An episode cannot be logged as asked (unknown task, time going backwards, ...)."""


class PrologError(NeemOracleError):
    """SWI-Prolog is missing or a Prolog query failed in a way the user can fix."""


class SettingsError(NeemOracleError):
    """Hyperparameter settings are malformed or out of range."""
