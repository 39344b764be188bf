"""validate/core/scenarios.py: the shared data folders are found (the variable, then beside
the checkout, then beside the working folder), never computed from where a module file
lies, which in a wheel install is site-packages (issue 23 item 6)."""
from pathlib import Path

from isorock.validate.tools.experiments import study
from isorock.validate.core import scenarios


def test_the_variable_names_the_folder(monkeypatch, tmp_path):
    monkeypatch.setenv("ISOROCK_VSR", str(tmp_path))
    assert scenarios.shared_folder("vsr", "ISOROCK_VSR") == tmp_path
    monkeypatch.setenv("ISOROCK_RECORDS", str(tmp_path / "r"))
    assert scenarios.records_folder() == tmp_path / "r"


def test_beside_the_working_folder_when_the_checkout_has_none(monkeypatch, tmp_path):
    """A wheel installed elsewhere, run from a checkout: `../shared/data/KIND` of the
    working folder, when the package's own surroundings hold no such folder."""
    monkeypatch.delenv("ISOROCK_VSR", raising=False)
    kind = "no-such-kind-here"
    (tmp_path / "shared" / "data" / kind).mkdir(parents=True)
    (tmp_path / "work").mkdir()
    monkeypatch.chdir(tmp_path / "work")
    assert scenarios.shared_folder(kind, "ISOROCK_VSR") == tmp_path / "shared" / "data" / kind


def test_none_found_names_the_checkouts_folder(monkeypatch, tmp_path):
    monkeypatch.delenv("ISOROCK_VSR", raising=False)
    monkeypatch.chdir(tmp_path)
    found = scenarios.shared_folder("no-such-kind-anywhere", "ISOROCK_VSR")
    assert found.parts[-3:] == ("shared", "data", "no-such-kind-anywhere") and not found.exists()
    assert Path(scenarios.__file__).resolve().parents[3] == found.parents[2]


def test_every_shared_folder_is_found_the_same_way():
    """The records and the shake-table tests lie side by side under shared/data."""
    assert study.default_data().parent == scenarios.RECORDS.parent
    assert scenarios.KOBE.parent == scenarios.RECORDS
