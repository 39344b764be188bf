"""isorock calibrate: its cases, the preset file it writes read back by validate's
--config path, and its refusals (the fit itself is measured, not timed, in the note)."""
import tomllib

import pytest

from isorock.analytic import paper_system
from isorock.validate.calibrate import FITTED, HELD_OUT, cases, settings_toml
from isorock.validate.cli import main
from isorock.validate.runner import resolve


def test_fitted_and_held_out_cases_cover_both_bases_and_never_overlap():
    fitted, held = cases(paper_system(fixed_base=True))
    assert len(fitted) == 2 * len(FITTED) and len(held) == 2 * len(HELD_OUT)
    assert {c.system.fixed_base for c in fitted} == {True, False} == {c.system.fixed_base for c in held}
    assert not {c.theta0_over_alpha for c in fitted} & {c.theta0_over_alpha for c in held}


@pytest.mark.parametrize("engine", ["mujoco", "bullet"])
def test_the_preset_file_reads_back_as_the_same_settings(engine):
    e, s = resolve(engine, {"timestep": 2e-3} if engine == "mujoco" else {})
    tuned = e.spec.tuning.apply(s, [b[0] + 0.3 * (b[1] - b[0]) for b in e.spec.tuning.bounds])
    table = tomllib.loads(settings_toml(engine, tuned, ["a header"]))["settings"][engine]
    assert resolve(engine, table)[1] == tuned


def test_an_engine_without_contact_parameters_is_refused(capsys):
    assert main(["calibrate", "--engine", "analytic"]) == 2
    err = capsys.readouterr().err
    assert "no contact parameters" in err and err.count("\n") == 1


def test_an_existing_output_file_is_never_replaced(tmp_path, capsys):
    out = tmp_path / "mine.toml"
    out.write_text("user's file\n")
    assert main(["calibrate", "--engine", "mujoco", "--out", str(out)]) == 2
    assert out.read_text() == "user's file\n"
