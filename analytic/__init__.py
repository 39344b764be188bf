"""The analytic reference: the hybrid rocking model and the vocabulary every engine
speaks (System, GroundMotion, Trajectory, closed-form coefficients)."""
from .coefficients import beta, beta2, beta3, beta_housner, no_bounce_slenderness, uplift_acceleration
from .errors import InputError
from .settings import AnalyticSettings
from .status import Status
from .motion import GroundMotion, Pulse, load_motion, parse_pulse, read_at2, read_jma, read_two_column
from .system import System, paper_system
from .trajectory import Impact, Trajectory

__all__ = [
    "System", "paper_system", "GroundMotion", "Pulse", "load_motion", "parse_pulse", "read_at2",
    "read_jma", "read_two_column", "Trajectory", "Impact", "AnalyticSettings", "simulate",
    "beta", "beta2", "beta3", "beta_housner", "no_bounce_slenderness", "uplift_acceleration",
    "InputError", "Status",
]


def __getattr__(name):
    # the SciPy reference path is imported on first use: importing SciPy's integrators
    # costs a new process ~0.3 s that the compiled engine does not need
    if name == "simulate":
        from .hybrid import simulate
        return simulate
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
