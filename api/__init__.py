"""isorock: cross-validation of multibody simulators on a statue rocking on a base-isolated
platform. The notebook API (isorock.validate.cli.api), loaded on first use so that
`import isorock.analytic` stays light:

    import isorock
    tr = isorock.run(engine="analytic", height=0.6, width=0.2, mass=80, base_mass=150, period=2.0,
                     damping_ratio=0.15, motion="sine:amp=0.3,freq=2,cycles=2", pga=0.5)
    tr.to_dataframe()
    report = isorock.report(quick=True, engines=["analytic", "mujoco"])   # isorock validate's report
    campaign = isorock.sweep("examples/spectrum.toml").to_dataframe()
    answer = isorock.design(height=0.6, width=0.2, mass=80, base_mass=150, pga=[0.2, 0.4])  # FEMA P695
    bust = isorock.System.isolated(height=0.6, width=0.2, mass=80, base_mass=150, period=2.0, damping_ratio=0.15)
    tr = isorock.simulate(bust, isorock.load_motion("sine:amp=0.5,freq=1,cycles=2"), engine="mujoco",
                          settings={"timestep": 2e-4})
    print(answer.headline); answer.to_dataframe()

The packages: isorock.analytic (the model), isorock.mujoco_models, isorock.bullet_models,
isorock.drake_models (the engines), isorock.validate (registry, measuring, reports, the
command line), isorock.validate.tools.campaign (sweeps), isorock.validate.tools.experiments (shake-table tests).
"""
from __future__ import annotations

import importlib

#: the entry points → the module holding the function of the same name: the command
#: `isorock validate` is `isorock.report(...)` here, since `isorock.validate` is the subpackage
#: (isorock.validate.core, …) and cannot also be a function; `design` takes Python values
#: (Statue's numbers, sequences, GroundMotions) and parses no command line
API = {"run": "isorock.validate.cli.api", "report": "isorock.validate.cli.api", "sweep": "isorock.validate.cli.api",
       "design": "isorock.validate.tools.campaign.answer",
       # typed, from Python values: one run of any engine, and the values it takes
       "simulate": "isorock.validate.core.plan", "System": "isorock.analytic.system",
       "GroundMotion": "isorock.analytic.motion", "load_motion": "isorock.analytic.motion"}


def __getattr__(name: str):
    if name in API:
        return getattr(importlib.import_module(API[name]), name)
    raise AttributeError(f"module 'isorock' has no attribute {name!r}")


__all__ = list(API)
