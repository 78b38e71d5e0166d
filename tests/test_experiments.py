"""experiments/ and scripts/ as experiments/README.md describes them: every reproduction has a row
in the index and parses, `make results` starts the reproduction of docs/results.md, and no text
of the project cites a script that is not there, unless it names the commit that holds it."""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
EXPERIMENTS = ROOT / "experiments"
INDEX = (EXPERIMENTS / "README.md").read_text(encoding="utf-8")
BASH = shutil.which("bash")
#: the text that may cite a script: pages, the build, the stack, the package and the reproductions
CITING = ("docs", "README.md", "Makefile", "docker", ".ci", "python", "experiments", "tests")
CITED = re.compile(r"\b(scripts|experiments)/([A-Za-z0-9_.-]+\.(?:py|sh))\b")
KEPT = re.compile(r"\b([0-9a-f]{7,40}):scripts/([A-Za-z0-9_.-]+\.(?:py|sh))\b")


def index_rows() -> dict[str, list[str]]:
    """Each index table's rows by section: ``{section: [file name of each row]}``."""
    rows: dict[str, list[str]] = {}
    section = ""
    for line in INDEX.splitlines():
        if line.startswith("## "):
            section = line[3:]
        found = re.match(r"\| `([^`]+)` \|", line)
        if found:
            rows.setdefault(section, []).append(found.group(1))
    return rows


def reproductions() -> list[Path]:
    return sorted(p for p in EXPERIMENTS.iterdir() if p.is_file() and p.name != "README.md")


def citing_files() -> list[Path]:
    files: list[Path] = []
    for name in CITING:
        path = ROOT / name
        found = [path] if path.is_file() else [p for p in path.rglob("*") if p.is_file()]
        files += [p for p in found if (p.suffix in {".md", ".py", ".sh", ".yml", ".yaml"} or p.name in {"Makefile", "run"})
                  and "__pycache__" not in p.parts and "secrets" not in p.parts]
    return [p for p in files if p.resolve() != Path(__file__).resolve()]


def git(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(["git", "-C", str(ROOT), *args], capture_output=True, text=True)


def test_every_reproduction_has_a_row_in_the_index_and_every_row_a_file():
    listed = {name for section, names in index_rows().items() if section != "Trials removed" for name in names}
    present = {p.name for p in reproductions()}
    assert present - listed == set(), f"experiments/README.md has no row for {sorted(present - listed)}"
    assert listed - present == set(), f"experiments/README.md lists files that are not there: {sorted(listed - present)}"


@pytest.mark.parametrize("path", [p for p in reproductions() if p.suffix == ".py"], ids=lambda p: p.name)
def test_a_python_reproduction_compiles(path: Path):
    compile(path.read_text(encoding="utf-8"), str(path), "exec")


@pytest.mark.skipif(BASH is None, reason="bash is not installed here")
@pytest.mark.parametrize("path", [p for p in reproductions() if p.suffix == ".sh"], ids=lambda p: p.name)
def test_a_shell_reproduction_parses(path: Path):
    done = subprocess.run([str(BASH), "-n", str(path)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr


@pytest.mark.skipif(BASH is None, reason="bash is not installed here")
def test_make_results_runs_the_reproduction_of_the_results_page():
    makefile = (ROOT / "Makefile").read_text(encoding="utf-8")
    recipe = re.search(r"^results:\n((?:\t.*\n)+)", makefile, re.MULTILINE)
    assert recipe and "experiments/make-results.sh" in recipe.group(1), "make results does not run experiments/make-results.sh"
    done = subprocess.run([str(BASH), str(EXPERIMENTS / "make-results.sh"), "--help"], capture_output=True, text=True)
    assert done.returncode == 0 and "docs/results.md" in done.stdout, done.stderr
    refused = subprocess.run([str(BASH), str(EXPERIMENTS / "make-results.sh"), "out"], capture_output=True, text=True)
    assert refused.returncode == 2 and "--help" in refused.stderr


def test_no_text_cites_a_script_that_is_not_there_unless_it_names_the_commit_that_holds_it():
    missing = []
    for path in citing_files():
        text = path.read_text(encoding="utf-8", errors="replace")
        kept = {name for _, name in KEPT.findall(text)}
        for folder, name in set(CITED.findall(text)):
            if not (ROOT / folder / name).exists() and not (folder == "scripts" and name in kept):
                missing.append(f"{path.relative_to(ROOT)}: {folder}/{name}")
    assert not missing, f"cited but not in the tree (nor named with `git show SHA:scripts/NAME`): {sorted(missing)}"


def test_scripts_holds_only_the_tools_the_build_the_stack_and_the_tests_call():
    callers = "".join(p.read_text(encoding="utf-8", errors="replace") for p in citing_files()
                      if p.parts[len(ROOT.parts)] in {"Makefile", "docker", ".ci", "tests"})
    unused = [p.name for p in (ROOT / "scripts").iterdir() if p.is_file() and p.name not in callers]
    assert not unused, f"scripts/ holds what neither make, CI, the docker stack nor a test calls: {unused}"


def kept_references() -> list[tuple[str, str]]:
    found = set()
    for path in citing_files():
        found |= set(KEPT.findall(path.read_text(encoding="utf-8", errors="replace")))
    return sorted(found)


def test_every_removed_trial_is_named_with_the_commit_that_holds_it():
    trials = index_rows().get("Trials removed", [])
    assert trials, "experiments/README.md has no 'Trials removed' table"
    for line in INDEX.splitlines():
        row = re.match(r"\| `([^`]+)` \| `([0-9a-f]{7,40})` \|", line)
        if row:
            assert not (ROOT / "scripts" / row.group(1)).exists(), f"{row.group(1)} is listed as removed"


@pytest.mark.skipif(shutil.which("git") is None, reason="git is not installed here")
def test_the_commits_named_for_removed_scripts_hold_them():
    if git("rev-parse", "--is-shallow-repository").stdout.strip() != "false":
        pytest.skip("not a full git clone: the commits that hold the removed scripts are not here")
    rows = re.findall(r"\| `([^`]+)` \| `([0-9a-f]{7,40})` \|", INDEX)
    wanted = sorted(set(kept_references()) | {(sha, name) for name, sha in rows})
    absent = [f"{sha}:scripts/{name}" for sha, name in wanted if git("cat-file", "-e", f"{sha}:scripts/{name}").returncode]
    assert not absent, f"named as holding a removed script, but do not: {absent}"
