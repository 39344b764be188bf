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


# --- item 6: a TOML file is bounded before any parser sees it, in one place ----------------

#: (text, what the refusal names): each once handed to tomllib as it was (a ValueError past
#: Python's 4,300-digit limit, a RecursionError, minutes of a quadratic walk)
HOSTILE_TOML = [
    ("height = " + "9" * 5000 + "\n", "digits"),
    ("x = " + "[" * 100_000 + "]" * 100_000 + "\n", "nested"),
    ("x = " + "{a = " * 50_000 + "1" + "}" * 50_000 + "\n", "nested"),
    (".".join(["a"] * 50_000) + " = 1\n", "parts"),
    ("[" + ".".join(["t"] * 50_000) + "]\n", "parts"),
    ("# pad\n" * 200_000, "MiB"),
]


def _readers():
    from isorock.campaign.spec import load_spec
    from isorock.validate.cli.config_file import read_config
    return {"config": read_config, "campaign": load_spec}


@pytest.mark.parametrize("reader", ["config", "campaign"])
@pytest.mark.parametrize("text, named", HOSTILE_TOML, ids=["digits", "arrays", "inline tables", "dotted key",
                                                          "table header", "size"])
def test_every_toml_reader_bounds_the_file_before_parsing_it(tmp_path, reader, text, named):
    path = tmp_path / "f.toml"
    path.write_text(text)
    with pytest.raises(InputError, match=named) as e:
        _readers()[reader](path)
    assert "f.toml" in str(e.value) and "\n" not in str(e.value)


def test_the_bounds_pass_what_a_lawful_file_holds():
    """Strings (with brackets, dots, digits and '#' in them), floats, dates, dotted keys and
    tables of every kind, as the scan sees them: the parser's own answer comes back."""
    from isorock.validate.io.schema import parse_toml
    text = ('a.b."c.d" = "x.y.z [[[{{{ 999 # not a comment"\n'
            "f = [1.5, 2.5e-3, 1979-05-27T07:32:00.999, 0x" + "f" * 900 + "]\n"
            "[t.u]\nv = {w.x = 1, y = [[1], [2]]}\n"
            "[[arr.of.tables]]\nlit = '''a . b\n[ ] ]'''\nml = \"\"\"q\\\"\"\" . [\"\"\"\n")
    import tomllib
    assert parse_toml(text.encode(), "where") == tomllib.loads(text)
    deep = "x = " + "[" * 32 + "]" * 32 + "\n"
    assert parse_toml(deep.encode(), "where") == tomllib.loads(deep)
    with pytest.raises(InputError, match="nested"):
        parse_toml(("x = " + "[" * 33 + "]" * 33 + "\n").encode(), "where")
