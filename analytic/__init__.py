"""The analytic reference: the hybrid rocking model and the vocabulary every engine
speaks (System, GroundMotion, Trajectory, closed-form coefficients).

Names are loaded on first use (PEP 562), so `import isorock.analytic.errors` or the
closed forms never pull in SciPy's integrators: `isorock beta` stays light.
"""
import importlib

_HOMES = {
    "beta": "coefficients", "beta2": "coefficients", "beta3": "coefficients", "beta_housner": "coefficients",
    "no_bounce_slenderness": "coefficients",
    "InputError": "errors",
    "AnalyticSettings": "settings", "simulate": "hybrid",
    "GroundMotion": "motion", "Pulse": "motion", "load_motion": "motion", "parse_pulse": "motion",
    "read_at2": "motion", "read_jma": "motion", "read_two_column": "motion",
    "Status": "status",
    "System": "system", "paper_system": "system",
    "Impact": "trajectory", "Trajectory": "trajectory", "RawHistory": "trajectory",
}

__all__ = sorted(_HOMES)


def __getattr__(name):
    home = _HOMES.get(name)
    if home is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f".{home}", __name__), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_HOMES))
