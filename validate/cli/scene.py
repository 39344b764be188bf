"""`isorock scene`: the model file a contact engine runs (its parser is main.py's)."""
from __future__ import annotations

import os
import sys

from ...analytic.errors import InputError
from ...analytic.system import PAPER_DAMPING_RATIO, PAPER_PERIOD
from ..core.engines import ALL_ENGINES, get_engine
from ..io.inputs import engine_settings_from_args, system_from_args
from ..io.output import Outputs


def cmd_scene(a) -> int:
    with Outputs() as outputs:
        # a model file is kept and edited: a file of that name is not replaced (as calibrate's
        # preset); standard output, a device or a pipe are written as streams
        regular = a.out != "-" and (os.path.isfile(a.out) or not os.path.lexists(a.out))
        out = outputs.file("out", a.out, exclusive=regular)
        engine = get_engine(a.engine)
        if not engine.has_scene:
            raise InputError(f"engine = {a.engine!r}: has no model file to write (those that do: "
                             f"{', '.join(_engines_with_scenes())})")
        system = system_from_args(a, default_isolator=(PAPER_PERIOD, PAPER_DAMPING_RATIO))
        settings = engine_settings_from_args(engine, a)
        out.write_text(engine.scene_text(system, settings))
        outputs.commit()
    if a.out == "-":
        return 0
    kind, suffix = engine.scene_format
    if not str(a.out).lower().endswith(suffix):
        print(f"note: {a.engine} scenes are {kind} files ({suffix}); {a.out} holds {kind}", file=sys.stderr)
    print(a.out)
    return 0


def _engines_with_scenes():
    out = []
    for name in ALL_ENGINES:
        try:
            if get_engine(name).has_scene:
                out.append(name)
        except ImportError:
            continue
    return out
