"""The DOP853 tableau (Dormand and Prince's explicit Runge-Kutta 8(5,3), with its 7th-order
dense output), exactly SciPy's, which is Hairer's: the compiled kernels' (analytic.fast,
analytic.slide_fast) one source of its coefficients.
"""
from __future__ import annotations

import importlib.util
import os

import numpy as np


def _dop853_coefficients():
    """SciPy's DOP853 tableau module, loaded from its file: importing it by name would
    first import all of scipy.integrate (~0.3 s of a new process's start)."""
    spec = importlib.util.find_spec("scipy")
    path = os.path.join(os.path.dirname(spec.origin), "integrate", "_ivp", "dop853_coefficients.py")
    if not os.path.exists(path):  # pragma: no cover - a SciPy that moved it
        from scipy.integrate._ivp import dop853_coefficients  # lazy: only where SciPy moved the file read above
        return dop853_coefficients
    spec = importlib.util.spec_from_file_location("_isorock_dop853_coefficients", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


_dop = _dop853_coefficients()
# DOP853 tableau, exactly SciPy's (which is Hairer's)
_A = np.ascontiguousarray(_dop.A, dtype=np.float64)  # (16, 16), rows 13-15 for dense output
_B = np.ascontiguousarray(_dop.B, dtype=np.float64)
_C = np.ascontiguousarray(_dop.C, dtype=np.float64)
_E3 = np.ascontiguousarray(_dop.E3, dtype=np.float64)
_E5 = np.ascontiguousarray(_dop.E5, dtype=np.float64)
_D = np.ascontiguousarray(_dop.D, dtype=np.float64)
