"""Issue 34's hostile-input defects (and issue 39's overlapping ones), each by its own test,
written before its fix; the breadth of hostile cases is tests/adversarial_round_three.py
(run by tests/test_adversarial.py)."""
from __future__ import annotations

import pytest

from isorock.analytic.errors import InputError
from isorock.validate.cli.main import main


def _one_line(capsys) -> str:
    err = capsys.readouterr().err
    assert err.count("\n") == 1, err
    return err


# --- item 4: an empty value is never replaced by a default -----------------------------------

@pytest.mark.parametrize("argv, option", [
    (["design", "--periods", ""], "--periods"),
    (["design", "--isolator", "ball-in-cone", "--slopes", " "], "--slopes"),
    (["design", "--config", ""], "--config"),
    (["design", "--records", ""], "--records"),
    (["validate", "--config", ""], "--config"),
    (["run", "--fixed-base", "--motion", ""], "--motion"),
    (["sweep", "c.toml", "--out", ""], "--out"),
    (["sweep", "c.toml", "--scheduler", ""], "--scheduler"),
    (["sweep", ""], "spec"),
    (["experiments", "--steps", ""], "--steps"),
])
def test_an_empty_value_is_refused_by_its_option(argv, option, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    err = _one_line(capsys)
    assert option in err and "empty" in err
    assert list(tmp_path.iterdir()) == []  # nothing ran, nothing written
