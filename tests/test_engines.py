"""Every registered engine speaks the same protocol: frozen validated Settings,
simulate(...) -> Trajectory with finite histories, deterministic, and the first
impact of free rocking at model.md's exact time (within each engine's resolution)."""
import dataclasses

import numpy as np
import pytest


from isorock.analytic import InputError, System, Trajectory
from isorock.analytic.engine_protocol import EngineSpec
from isorock.validate.core.compare import exact_first_impact_time
from isorock.validate.core.engines import ALL_ENGINES, ENGINE_NAMES, get_engine
from isorock.validate.core.tolerances import tolerance
from isorock.validate.tools.bench import LADDER

SYSTEM = System.fixed(height=2.0, width=0.7, mass=3800.0)
FIRST_IMPACT = exact_first_impact_time(SYSTEM, 0.5 * SYSTEM.alpha)  # model.md: 0.5014170 s


def _importable(name):
    try:
        get_engine(name)
        return True
    except ImportError:
        return False


@pytest.fixture(params=ALL_ENGINES)
def engine(request):
    if not _importable(request.param):
        pytest.skip(f"engine {request.param} cannot be imported here")
    return get_engine(request.param)


def test_registry_names():
    assert set(ENGINE_NAMES) <= set(ALL_ENGINES)
    with pytest.raises(InputError, match="engine = 'ode45'"):
        get_engine("ode45")


def test_settings_frozen_and_overrides_checked(engine):
    s = engine.settings()
    assert dataclasses.is_dataclass(s)
    with pytest.raises(dataclasses.FrozenInstanceError):
        s.__setattr__(dataclasses.fields(s)[0].name, 1)
    with pytest.raises(InputError, match="not a setting"):
        engine.settings(warp_drive=1)


def test_free_rocking_protocol(engine):
    runs = [engine.simulate(SYSTEM, None, duration=1.5, theta0=0.5 * SYSTEM.alpha) for _ in range(2)]
    a, b = runs
    # "analytic-fast" is the former name of "analytic": its runs say the engine's name
    assert isinstance(a, Trajectory) and a.engine == {"analytic-fast": "analytic"}.get(engine.name, engine.name)
    for name in ("t", "u", "u_dot", "theta", "theta_dot"):
        x = getattr(a, name)
        assert x.shape == a.t.shape and np.all(np.isfinite(x)), name
        np.testing.assert_array_equal(x, getattr(b, name), err_msg=f"{name} differs between two runs")
    assert a.t[-1] == pytest.approx(1.5, abs=1e-9)
    assert a.theta_max_over_alpha == pytest.approx(0.5, abs=1e-3)
    first = a.counted_impacts[0]
    assert first.t == pytest.approx(FIRST_IMPACT, rel=tolerance(engine.name, "first_impact_time_rel_error").limit)
    assert a.summary()["impacts"] == a.impact_count >= 2


def test_every_engine_states_its_protocol(engine):
    spec = engine.spec
    assert isinstance(spec, EngineSpec) and spec.name == {"analytic-fast": "analytic"}.get(engine.name, engine.name)
    assert spec.label
    assert "default" in spec.presets
    for name in spec.presets:
        assert isinstance(engine.preset(name), engine.Settings), name
    with pytest.raises(InputError, match="not a preset"):
        engine.preset("warp")
    if engine.has_scene:
        kind, suffix = engine.scene_format
        assert kind and suffix.startswith(".") and engine.scene_text(SYSTEM, engine.settings()).strip()
    for label, settings in (LADDER.of(spec) or (lambda quick: []))(True):
        assert label and isinstance(settings, engine.Settings)


def test_every_contact_impact_is_logged_with_its_counted_flag(engine):
    """impacts_total means the same for every engine: every sign change of θ."""
    tr = engine.simulate(SYSTEM, None, duration=1.5, theta0=0.5 * SYSTEM.alpha)
    assert len(tr.impacts) >= tr.impact_count and tr.summary()["impacts_total"] == len(tr.impacts)
    assert all(i.counted == (i.amplitude > tr.impact_threshold * SYSTEM.alpha) for i in tr.impacts)


def test_a_built_in_engine_whose_extra_is_absent_is_one_line_where_named(monkeypatch, capsys):
    """Drake without pydrake: skipped where every engine is looped over (an ImportError), one line
    where a command names it (exit 2), never a traceback."""
    import sys

    from isorock.validate.cli.main import main
    monkeypatch.setitem(sys.modules, "pydrake", None)  # found nowhere, as where it is not installed
    for name in [m for m in sys.modules if m.startswith("isorock.drake_models")]:
        monkeypatch.delitem(sys.modules, name)
    with pytest.raises(ImportError):
        get_engine("drake")
    assert main(["presets", "drake"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "isorock[drake]" in err
