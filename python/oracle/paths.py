"""Where the shipped data lives: ``ontology/`` (odb, mapping, core TBox, world) and ``prolog/``.

A source checkout (editable install) finds them beside the package; an installed copy (as in the
Docker image) is pointed at them by ``NEEM_ORACLE_HOME``, else looks in the working directory.
"""

from __future__ import annotations

import os
from pathlib import Path

_CHECKOUT = Path(__file__).resolve().parents[2]


def project_home() -> Path:
    override = os.environ.get("NEEM_ORACLE_HOME")
    if override:
        return Path(override)
    if (_CHECKOUT / "ontology").is_dir():
        return _CHECKOUT
    return Path.cwd()


def data_dir() -> Path:
    return project_home() / "ontology"


def prolog_dir() -> Path:
    return project_home() / "prolog"
