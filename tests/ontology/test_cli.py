import json
import subprocess
import sys

from oracle.cli import main


def test_build_writes_owl_and_prints_summary(tmp_path, capsys):
    out = tmp_path / "odb.owl"
    assert main(["ontology", "build", "--out", str(out), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert out.exists() and summary["objects"] == 73 and summary["unmapped_objects"] == ["_object"]


def test_distance_from_written_file(tmp_path, capsys):
    out = tmp_path / "odb.ttl"
    assert main(["ontology", "build", "--out", str(out)]) == 0
    capsys.readouterr()
    assert main(["ontology", "distance", "red_mug", "green_mug", "--ontology", str(out), "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["lcs"].endswith("#_mug") and result["path"] == 2 and result["distance"] > 0


def test_bad_input_gives_one_line_and_exit_1(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "oracle", "ontology", "build", "--odb", str(tmp_path), "--out", str(tmp_path / "x.owl")],
                          capture_output=True, text=True)
    assert proc.returncode == 1
    assert proc.stderr.count("\n") == 1 and "no */manifest.xml found" in proc.stderr
    proc = subprocess.run([sys.executable, "-m", "oracle", "ontology", "distance", "red_mug", "unicorn"], capture_output=True, text=True)
    assert proc.returncode == 1 and "unknown class 'unicorn'" in proc.stderr


def test_distance_takes_prefixed_names_from_a_written_file(tmp_path, capsys):
    """soma:/dul: CURIEs resolve as in the mapping, also for an ontology read back from RDF/XML."""
    out = tmp_path / "kitchen.owl"
    assert main(["ontology", "build", "--out", str(out)]) == 0
    capsys.readouterr()
    for extra in ([], ["--ontology", str(out)]):
        assert main(["ontology", "distance", "pick", "soma:Pouring", "--json", *extra]) == 0
        result = json.loads(capsys.readouterr().out)
        assert result["b"] == "http://www.ease-crc.org/ont/SOMA.owl#Pouring" and result["distance"] > 0
    assert main(["ontology", "distance", "pick", "soma:NoSuchTask", "--ontology", str(out)]) == 1
    assert "unknown class soma:NoSuchTask" in capsys.readouterr().err
