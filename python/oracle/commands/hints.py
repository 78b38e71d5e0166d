"""The command line a hint prints, runnable as printed: the interpreter that runs this one."""

from __future__ import annotations

import os
import shlex
import sys
from pathlib import Path


def runnable() -> str:
    """``python -m oracle`` as this process was started: the interpreter's path (a venv's
    ``.venv/bin/python``, relative to the working folder when it lies below it), so a hint works
    outside an activated venv."""
    python = Path(sys.executable or "python3")
    try:
        shown = str(python.relative_to(Path.cwd()))
    except ValueError:
        shown = str(python)
    if os.sep not in shown:
        shown = f".{os.sep}{shown}" if (Path.cwd() / shown).exists() else shown
    return f"{shlex.quote(shown)} -m oracle"
