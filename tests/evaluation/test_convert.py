import re
import subprocess
import sys
from collections import Counter
from pathlib import Path

import pytest
import yaml

from oracle.chains import read_chains
from oracle.errors import NeemOracleError
from oracle.evaluation import convert_egtea, convert_kasteren
from oracle.ontology.mapping import load_mapping
from oracle.ontology.odb import read_odb

DATASETS = Path(__file__).resolve().parents[3] / "shared" / "datasets"
KASTEREN = DATASETS / "kasteren_house_a"
EGTEA = DATASETS / "egtea_gaze_plus"
SOMA_FILES = [Path(__file__).resolve().parents[3] / "shared" / "soma" / name for name in ("SOMA-HOME.owl", "DUL.owl")]

needs_kasteren = pytest.mark.skipif(not KASTEREN.is_dir(), reason=f"van Kasteren data not at {KASTEREN}")
needs_egtea = pytest.mark.skipif(not EGTEA.is_dir(), reason=f"EGTEA Gaze+ data not at {EGTEA}")


def declared_iris() -> set[str]:
    if not all(path.exists() for path in SOMA_FILES):
        pytest.skip(f"SOMA/DUL OWL files not at {SOMA_FILES[0].parent}")
    text = "".join(path.read_text(encoding="utf-8") for path in SOMA_FILES)
    return set(re.findall(r'<owl:Class rdf:about="([^"]+)"', text))


def check_output(out: Path) -> list:
    """Chains parse, every object has a manifest, every task a mapping entry and the object's snippet."""
    rows = list(read_chains(out / "chains.jsonl"))
    odb = read_odb(out / "odb")
    mapping = load_mapping(out / "mapping.yaml")
    for row in rows:
        assert row.action.task in mapping.actions, row.action
        for arg in row.action.args:
            assert row.action.task in odb[arg].tasks, row.action
    for obj in odb.values():
        assert obj.abstract or obj.parents, f"{obj.name} derives from nothing"
    raw = yaml.safe_load((out / "mapping.yaml").read_text())
    assert set(raw) == {"namespace", "imports", "soma_odb_map", "root_object", "action_defaults", "actions"}
    assert set(raw["action_defaults"]) == {"task", "ref_role", "target_role", "disposition"}
    return rows


def check_iris(out: Path) -> None:
    mapping = load_mapping(out / "mapping.yaml")
    iris = declared_iris()
    used = set(mapping.object_map.values()) | {mapping.root_object}
    for action in [mapping.defaults, *mapping.actions.values()]:
        used |= {v for v in (action.task, action.ref_role, action.target_role, action.disposition) if v}
    missing = sorted(iri for iri in used if iri not in iris)
    assert not missing, f"not declared in SOMA/DUL: {missing}"


# --- small fixtures that need no download -----------------------------------------------------------
def fake_kasteren(folder: Path) -> Path:
    (folder / "original").mkdir(parents=True)
    (folder / "original" / "kasterenSenseData.txt").write_text(
        "Sensor IDs are:\n    [ 7]    'Cups cupboard'\n    [ 8]    'Fridge'\n    [14]    'ToiletFlush'\n\n"
        "Start time          \tEnd time            \tID\tVal\n--\t--\t--\t---\n"
        "25-Feb-2008 09:49:27\t25-Feb-2008 09:49:30\t8\t1\n"
        "25-Feb-2008 09:37:51\t25-Feb-2008 09:37:52\t14\t1\n"
        "25-Feb-2008 09:50:02\t25-Feb-2008 09:50:09\t7\t1\n",
        encoding="latin-1",
    )
    (folder / "original" / "kasterenActData.txt").write_text(
        "activity id list:\n4: 'use toilet'\n13:'prepare Breakfast'\n\nStart time\tEnd time\tID\n--\t--\t--\n"
        "25-Feb-2008 09:37:17\t25-Feb-2008 09:38:02\t4\n25-Feb-2008 09:49:23\t25-Feb-2008 09:53:28\t13\n",
        encoding="latin-1",
    )
    return folder


def test_kasteren_fixture_becomes_a_timed_chain(tmp_path):
    report = convert_kasteren.convert(fake_kasteren(tmp_path / "k"), tmp_path / "out")
    rows = check_output(tmp_path / "out")
    assert [str(r.action) for r in rows] == ["flush(toilet_flush)", "open_fridge(fridge)", "open_cupboard(cups_cupboard)"]
    assert [r.extra.get("activity") for r in rows] == ["use toilet", "prepare Breakfast", "prepare Breakfast"]
    assert rows[0].time.isoformat() == "2008-02-25T09:37:51"
    assert rows[0].available is None
    assert report.actions == 3


def test_kasteren_unknown_sensor_names_the_line(tmp_path):
    folder = fake_kasteren(tmp_path / "k")
    path = folder / "original" / "kasterenSenseData.txt"
    path.write_text(path.read_text(encoding="latin-1") + "25-Feb-2008 10:00:00\t25-Feb-2008 10:00:01\t99\t1\n",
                    encoding="latin-1")
    with pytest.raises(NeemOracleError, match=r"kasterenSenseData.txt:\d+: unknown sensor id 99"):
        convert_kasteren.read_kasteren(folder)


def test_missing_dataset_folder_is_a_user_error(tmp_path):
    with pytest.raises(NeemOracleError, match="kasteren_house_a folder"):
        convert_kasteren.convert(tmp_path / "nothing", tmp_path / "out")
    with pytest.raises(NeemOracleError, match="egtea_gaze_plus folder"):
        convert_egtea.convert(tmp_path / "nothing", tmp_path / "out")


def test_egtea_fixture_orders_sessions_and_frames(tmp_path):
    folder = tmp_path / "e"
    folder.mkdir()
    (folder / "actions.csv").write_text("0, 0_0, Inspect/Read_recipe\n1, 1_1, Open_fridge\n2, 2_2, Take_eating:utensil\n")
    (folder / "training1.csv").write_text("5,P01-R02-Salad,300,310,2,2,2\n6,P01-R01-Pasta,900,910,1,1,1\n")
    (folder / "validation1.csv").write_text("7,P01-R01-Pasta,100,120,0,0,0\n8,OP02-R01-Pasta,5,9,1,1,1\n")
    convert_egtea.convert(folder, tmp_path / "out")
    rows = check_output(tmp_path / "out")
    assert [(r.user, str(r.action)) for r in rows] == [
        ("OP02", "open(fridge)"), ("P01", "inspect_read(recipe)"), ("P01", "open(fridge)"), ("P01", "take(eating_utensil)"),
    ]
    assert all(r.time is None for r in rows)
    assert rows[1].extra == {"session": "P01-R01-Pasta"}


def test_snake_case_names():
    assert convert_egtea.snake("Divide/Pull Apart") == "divide_pull_apart"
    assert convert_egtea.snake("eating:utensil") == "eating_utensil"
    assert convert_egtea.snake("Turn on") == "turn_on"


# --- the real data ------------------------------------------------------------------------------------
@needs_kasteren
def test_kasteren_house_a(tmp_path):
    report = convert_kasteren.convert(KASTEREN, tmp_path)
    rows = check_output(tmp_path)
    assert report.actions == len(rows) == 1319
    assert {r.user for r in rows} == {"kasteren-house-a"}
    times = [r.time for r in rows]
    assert times == sorted(times)
    assert len({r.action for r in rows}) == 14
    assert sum(1 for r in rows if "activity" in r.extra) > 800
    check_iris(tmp_path)


@needs_egtea
def test_egtea_gaze_plus(tmp_path):
    report = convert_egtea.convert(EGTEA, tmp_path)
    rows = check_output(tmp_path)
    assert report.actions == len(rows) == 10321
    assert len({r.user for r in rows}) == 32
    sessions = [r.extra["session"] for r in rows]
    assert len(set(sessions)) == 86
    # each session is one contiguous block inside its subject's chain
    blocks = [s for i, s in enumerate(sessions) if i == 0 or sessions[i - 1] != s]
    assert len(blocks) == 86
    assert Counter(str(r.action) for r in rows).most_common(1)[0][1] > 100
    assert len({str(r.action) for r in rows}) == 106
    check_iris(tmp_path)


@needs_kasteren
def test_cli_convert(tmp_path):
    result = subprocess.run([sys.executable, "-m", "oracle", "convert", "kasteren", str(KASTEREN), "--out", str(tmp_path)],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    assert "1319 actions" in result.stdout
    bad = subprocess.run([sys.executable, "-m", "oracle", "convert", "egtea", str(tmp_path / "absent"), "--out", str(tmp_path)],
                         capture_output=True, text=True, timeout=120)
    assert bad.returncode == 1 and bad.stderr.startswith("error:")


# --- converted chains import and evaluate ----------------------------------------------------------
def _import_and_evaluate(out: Path, tmp_path: Path) -> tuple[int, str]:
    from oracle.cli import main

    onto = ["--odb", str(out / "odb"), "--mapping", str(out / "mapping.yaml")]
    assert main(["import", str(out / "chains.jsonl"), "--store", str(tmp_path / "s.sqlite"), *onto]) == 0
    assert main(["evaluate", str(out / "chains.jsonl"), *onto]) == 0
    from oracle.neem.query import summarize_neem as summarize
    from oracle.store import open_store

    with open_store(tmp_path / "s.sqlite") as store:
        (info,) = store.neems()
        return summarize(store, info.id).actions, info.meta["alias"]  # its name (the id is an ObjectId)


def test_overlapping_kasteren_firings_import(tmp_path, capsys):
    """Sensor firings overlap (the fridge is still open when the cups cupboard opens): the chains
    keep them as they happened, and the logger takes overlapping actions."""
    folder = fake_kasteren(tmp_path / "k")
    path = folder / "original" / "kasterenSenseData.txt"
    path.write_text(path.read_text(encoding="latin-1") + "25-Feb-2008 09:49:29\t25-Feb-2008 09:50:30\t7\t1\n",
                    encoding="latin-1")
    convert_kasteren.convert(folder, tmp_path / "out")
    rows = check_output(tmp_path / "out")
    assert rows[1].end > rows[2].time  # the overlap is in the chains, not smoothed away
    actions, _ = _import_and_evaluate(tmp_path / "out", tmp_path)
    assert actions >= 4


@needs_kasteren
def test_kasteren_house_a_imports_and_evaluates(tmp_path, capsys):
    convert_kasteren.convert(KASTEREN, tmp_path / "out")
    actions, neem = _import_and_evaluate(tmp_path / "out", tmp_path)
    assert neem == "kasteren-house-a" and actions >= 1319  # every firing, plus idle actions
