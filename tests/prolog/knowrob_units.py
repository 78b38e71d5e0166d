"""KnowRob 2.x's own plunit units, taken as they are from a KnowRob source and run over prolog/.

The units live inside KnowRob's modules (`:- begin_rdf_tests(...)` ... `:- end_rdf_tests(...)`)
and in `.plt` files; their text is loaded unchanged after prolog/compat/knowrob_tests.pl, with
only the file's own `use_module` lines of KnowRob libraries left out. The OWL files they load
(`package://knowrob/owl/test/...`) come from the same source, through `$KNOWROB_PACKAGE_PATH`.
Nothing of KnowRob is stored in this repository: a source is found at `$KNOWROB_SRC` (a checkout)
or in the git mirror at `$KNOWROB_GIT`, else the tests skip.
"""

from __future__ import annotations

import os
import re
import subprocess
from dataclasses import dataclass
from pathlib import Path

DEFAULT_GIT = Path("/work/.mirror/knowrob+knowrob/repo")

#: The units of the modules this project mirrors (the 253 tests KnowRob's lang, mongolog builtins,
#: OWL, interval, workflow and tf units hold) ...
UNITS = (
    "src/lang/query.pl", "src/lang/scope.pl", "src/lang/computable.pl", "src/lang/terms/annotation.pl",
    "src/lang/mongolog/arithmetic.pl", "src/lang/mongolog/atoms.pl", "src/lang/mongolog/comparison.pl",
    "src/lang/mongolog/control.pl", "src/lang/mongolog/findall.pl", "src/lang/mongolog/lists.pl",
    "src/lang/mongolog/meta.pl", "src/lang/mongolog/sgml.pl", "src/lang/mongolog/terms.pl",
    "src/lang/mongolog/typecheck.pl", "src/lang/mongolog/unification.pl",
    "src/model/OWL.plt", "src/reasoning/temporal/interval.plt", "src/reasoning/temporal/workflow.pl",
    "src/ros/tf/tf.plt",
)  # fmt: skip
#: ... and those compat/knowrob_2x.plt restates over fixtures of its own (60 tests).
RESTATED = (
    "src/lang/terms/triple.plt", "src/lang/terms/holds.pl", "src/lang/terms/temporal.pl", "src/model/RDFS.pl",
    "src/model/NEEM.pl", "src/model/terms.pl",
)  # fmt: skip

_BEGIN = re.compile(r"^:-\s*begin_(?:rdf_)?tests\(\s*'?([\w]+)'?", re.M)
_END = re.compile(r"^:-\s*end_(?:rdf_)?tests\([^)]*\)\s*\.[ \t]*$", re.M)


@dataclass(frozen=True)
class Unit:
    """One plunit unit of KnowRob: its name, the file it is in, and its text."""

    name: str
    source: str
    text: str


class KnowRobSource:
    """Files of a KnowRob checkout (``$KNOWROB_SRC``) or of its git mirror (``$KNOWROB_GIT``)."""

    def __init__(self, checkout: Path | None, git: Path | None) -> None:
        self.checkout, self.git = checkout, git

    @classmethod
    def find(cls) -> KnowRobSource | None:
        if os.environ.get("KNOWROB_SRC"):
            folder = Path(os.environ["KNOWROB_SRC"])
            return cls(folder, None) if (folder / "src").is_dir() else None
        git = Path(os.environ.get("KNOWROB_GIT", DEFAULT_GIT))
        return cls(None, git) if git.is_dir() else None

    def read(self, path: str) -> str:
        if self.checkout is not None:
            return (self.checkout / path).read_text(encoding="utf-8")
        assert self.git is not None
        done = subprocess.run(["git", "-C", str(self.git), "show", f"master:{path}"], capture_output=True, text=True)
        if done.returncode != 0:
            raise FileNotFoundError(path)
        return done.stdout

    def files(self, folder: str) -> list[str]:
        if self.checkout is not None:
            return sorted(str(p.relative_to(self.checkout)) for p in (self.checkout / folder).glob("*") if p.is_file())
        assert self.git is not None
        done = subprocess.run(["git", "-C", str(self.git), "ls-tree", "--name-only", f"master:{folder}"],
                              capture_output=True, text=True, check=True)
        return [f"{folder}/{name}" for name in done.stdout.split()]

    def package_path(self, into: Path) -> Path:
        """A folder holding package ``knowrob`` with its test OWL files, for ``$KNOWROB_PACKAGE_PATH``."""
        if self.checkout is not None:
            return self.checkout.parent if self.checkout.name == "knowrob" else self._copy(into)
        return self._copy(into)

    def _copy(self, into: Path) -> Path:
        target = into / "knowrob" / "owl" / "test"
        target.mkdir(parents=True, exist_ok=True)
        for path in self.files("owl/test"):
            (target / Path(path).name).write_text(self.read(path), encoding="utf-8")
        return into


def units(source: KnowRobSource, paths: tuple[str, ...]) -> list[Unit]:
    """Every unit of the files, its text as KnowRob wrote it (a `.plt` from its first unit on)."""
    found = []
    for path in paths:
        text = source.read(path)
        for begin in _BEGIN.finditer(text):
            end = _END.search(text, begin.end())
            if end is None:
                raise ValueError(f"{path}: unit {begin.group(1)} has no end")
            found.append(Unit(begin.group(1), path, text[begin.start():end.end()] + "\n"))
    return found


def write_units(found: list[Unit], folder: Path) -> list[Path]:
    files = []
    for i, unit in enumerate(found):
        path = folder / f"{i:02d}_{unit.name}.pl"
        path.write_text(unit.text, encoding="utf-8")
        files.append(path)
    return files
