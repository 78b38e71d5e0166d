"""Where the shipped data lives: ``ontology/`` (odb, mapping, core TBox, world) and ``prolog/``.

A source checkout (also an editable install) uses the folders at its top; a wheel carries copies
inside the package (``oracle/_data/``, written by setup.py). ``NEEM_ORACLE_HOME`` overrides both
with a folder holding ``ontology/`` and ``prolog/``.
"""

from __future__ import annotations

import os
from pathlib import Path

_PACKAGE = Path(__file__).resolve().parent
_CHECKOUT = _PACKAGE.parents[1]
_INSTALLED = _PACKAGE / "_data"


def project_home() -> Path:
    override = os.environ.get("NEEM_ORACLE_HOME")
    if override:
        return Path(override)
    if (_CHECKOUT / "ontology").is_dir() and (_CHECKOUT / "prolog").is_dir():
        return _CHECKOUT
    return _INSTALLED


def data_dir() -> Path:
    return project_home() / "ontology"


def prolog_dir() -> Path:
    return project_home() / "prolog"
