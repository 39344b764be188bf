"""The isolators a contact engine does not carry are refused in one line, from Python and from the
command line (exit 2), never run as another: Drake and DART carry the linear isolator, the friction
pendulum and the ball in a bowl (docs/isolators.md, "Who carries what"), and refuse the bilinear
bearing, the ball in a cone, the double pendulum and a velocity-dependent friction."""
from __future__ import annotations

import importlib.util

import pytest

from test_two_components import SLIDING_PULSE, STILL_BLOCK

from isorock.analytic.errors import InputError
from isorock.analytic.motion import load_motion
from isorock.analytic.system import BallInCone, BilinearIsolator, DoubleFrictionPendulum, FrictionPendulum, System
from isorock.validate.cli.main import main
from isorock.validate.core.engines import get_engine

#: engine → the module it needs (skipped where its extra is not installed)
ENGINES = {"drake": "pydrake", "dart": "dartpy"}


def _engine(name):
    if importlib.util.find_spec(ENGINES[name]) is None:
        pytest.skip(f"{ENGINES[name]} is not installed (the {name} extra)")
    return get_engine(name)


@pytest.mark.parametrize("engine", list(ENGINES))
@pytest.mark.parametrize("isolator, named", [
    (BilinearIsolator(stiffness=3e5, post_yield_ratio=0.5, yield_displacement=0.005), "isolator = bilinear"),
    (BallInCone(slope=0.1, rolling_resistance=0.01), "isolator = ball-in-cone"),
    (DoubleFrictionPendulum(1.0, 0.03, 1.0, 0.06), "isolator = double-friction-pendulum"),
    (FrictionPendulum(radius=1.0, friction_coefficient=0.05, friction_max=0.1, friction_rate=20.0),
     "friction_rate"),
], ids=["bilinear", "ball-in-cone", "double-pendulum", "friction-rate"])
def test_the_other_isolators_are_refused_in_one_line(engine, isolator, named):
    system = System.with_isolator(**STILL_BLOCK, isolator=isolator)
    with pytest.raises(InputError, match=named) as e:
        _engine(engine).simulate(system, load_motion(SLIDING_PULSE), duration=1.0)
    assert "\n" not in str(e.value)


@pytest.mark.parametrize("engine", list(ENGINES))
def test_the_command_refuses_them_in_one_line_exit_2(engine, capsys):
    _engine(engine)
    block = ["--height", "2.0", "--width", "0.7", "--mass", "1000", "--base-mass", "1000", "--engine", engine]
    for args, named in ((["--isolator", "bilinear", "--stiffness", "1e5", "--post-yield-ratio", "0.1",
                          "--yield-displacement", "0.01"], "isolator = bilinear"),
                        (["--isolator", "ball-in-cone", "--slope", "0.1", "--rolling-resistance", "0.01"],
                         "isolator = ball-in-cone")):
        code = main(["run", *block, *args, "--motion", "sine:amp=0.3,freq=1,cycles=1"])
        err = capsys.readouterr().err.strip()
        assert code == 2 and len(err.splitlines()) == 1 and named in err, err
