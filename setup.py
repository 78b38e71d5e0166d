"""Ships the data folders ``ontology/`` and ``prolog/`` inside the wheel as ``oracle/_data/``.

They live at the top of the checkout (where a source checkout and the Makefile use them), so
setuptools' package data cannot name them; the metadata is in pyproject.toml.
"""

import shutil
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py

DATA_FOLDERS = ("ontology", "prolog")


class BuildWithData(build_py):
    def run(self) -> None:
        super().run()
        if getattr(self, "editable_mode", False):
            return  # an editable install reads the checkout's folders (oracle/paths.py)
        here = Path(__file__).resolve().parent
        for name in DATA_FOLDERS:
            target = Path(self.build_lib) / "oracle" / "_data" / name
            shutil.rmtree(target, ignore_errors=True)
            shutil.copytree(here / name, target, ignore=shutil.ignore_patterns("__pycache__", "*.pyc", "*.plt"))


setup(cmdclass={"build_py": BuildWithData})
