"""One run's summary row: the columns every table of runs shares (campaign tables,
ensembles, the agreement maps), built from a Trajectory or from a batch result of the
compiled kernel, in one place. The schema is the one home of the columns' names and
types; `rows_to_table` makes a pyarrow table of rows."""
from __future__ import annotations

import math

# The table's schema: one home. Inputs first (what defines a case), then results.
INPUT_COLUMNS = {
    "case": "int64", "engine": "string", "setting": "string",
    "base": "string", "height": "float64", "width": "float64", "slenderness": "float64",
    "alpha": "float64", "size": "float64", "p": "float64", "mass": "float64",
    "mass_ratio": "float64", "period": "float64", "damping_ratio": "float64",
    "motion": "string", "cycles": "float64", "frequency_ratio": "float64",
    "amplitude_ratio": "float64", "pulse_amp_g": "float64", "pulse_freq_hz": "float64",
    "scale_by": "string", "intensity": "float64", "scale_factor": "float64",
    "duration": "float64", "theta0": "float64",
    # the statue's friction on its base (docs/sliding.md; NaN: it cannot slip)
    "friction": "float64",
    # a statue's own mesh (docs/statues.md; "" : the block H × B) and the direction it is shaken
    # along, degrees from the mesh's x towards y (NaN for the block)
    "statue": "string", "azimuth": "float64",
}
RESULT_COLUMNS = {
    "status": "string", "message": "string", "theta_max_over_alpha": "float64",
    "overturned": "bool", "overturn_mode": "string", "overturn_time": "float64",
    "impacts": "int64", "uplift": "bool", "uplifts": "int64", "u_max": "float64",
    # m: how far the statue walked on its base at most (NaN where it cannot slip)
    "slide_max": "float64",
    "runtime_s": "float64",
}
COLUMNS = {**INPUT_COLUMNS, **RESULT_COLUMNS}
#: The one column allowed to differ between two runs of the same campaign.
NONDETERMINISTIC_COLUMNS = ("runtime_s",)
SORT_KEYS = ("case", "engine", "setting")

NOT_OVERTURNED, WITHOUT_IMPACT, AFTER_IMPACTS = "none", "without impact", "after impacts"


def schema():
    import pyarrow as pa  # lazy: pyarrow only where a table is built
    types = {"int64": pa.int64(), "float64": pa.float64(), "string": pa.string(), "bool": pa.bool_()}
    return pa.schema([(k, types[v]) for k, v in COLUMNS.items()])


#: The last System's columns and the System itself: a table's cases come in runs of one system
#: (a design's 440 runs per isolator), and its properties cost microseconds each, which over a
#: design's 176,440 rows was seconds of one core. A System is frozen, so its columns are too.
_LAST_SYSTEM: tuple = (None, {})


def system_inputs(s) -> dict:
    """The table's input columns that the System gives."""
    global _LAST_SYSTEM
    last = _LAST_SYSTEM  # one read: threads may replace it, never mutate it
    if last[0] is s:
        return last[1]
    columns = dict(base="fixed" if s.fixed_base else "isolated", height=s.height, width=s.width,
                   slenderness=s.slenderness, alpha=s.alpha, size=s.R, p=s.p, mass=s.mass,
                   mass_ratio=s.mu, period=math.nan if s.fixed_base else s.period,
                   damping_ratio=math.nan if s.fixed_base else s.damping_ratio,
                   friction=math.nan if s.friction is None else s.friction)
    _LAST_SYSTEM = (s, columns)
    return columns


_BLANK_INPUTS = {k: (math.nan if t == "float64" else "") for k, t in INPUT_COLUMNS.items() if t != "int64"}


def case_inputs(case: Case) -> dict:
    """The table's input columns for a case: the system's from the System itself (so an
    in-memory case needs nothing else), the motion's from `inputs` where given."""
    row = {**_BLANK_INPUTS, **system_inputs(case.system), "motion": getattr(case.motion, "name", ""),
           "duration": case.duration, "theta0": case.theta0}
    row.update({k: v for k, v in case.inputs.items() if k in INPUT_COLUMNS})
    row["case"] = case.case
    return row


def overturn_mode(overturned: bool, impacts_before: int) -> str:
    if not overturned:
        return NOT_OVERTURNED
    return WITHOUT_IMPACT if impacts_before == 0 else AFTER_IMPACTS



def row_of_batch(case, result: dict) -> dict:
    """The result columns of one case of `analytic.fast.simulate_batch`."""
    overturned = bool(result["overturned"])
    # a batch run stops when the block falls, so its impacts all precede it
    # a failed case says why (the kernel's message); others need no words
    return {"status": str(result["status"]), "message": str(result.get("message", "")),
            "theta_max_over_alpha": float(result["theta_max_over_alpha"]), "overturned": overturned,
            "overturn_mode": overturn_mode(overturned, int(result["impacts"])),
            "overturn_time": math.nan if result["overturn_time"] is None else float(result["overturn_time"]),
            "impacts": int(result["impacts"]), "uplift": int(result["uplifts"]) > 0,
            "uplifts": int(result["uplifts"]), "u_max": float(result["u_max"]),
            "slide_max": float(result.get("slide_max", math.nan))}


def row_of_trajectory(tr) -> dict:
    """The result columns of a measured Trajectory (any engine)."""
    t_fall = tr.overturn_time if tr.overturned and tr.overturn_time is not None else math.inf
    before = sum(1 for i in tr.counted_impacts if i.t <= t_fall)
    return {"status": str(tr.status), "message": tr.message,
            "theta_max_over_alpha": tr.theta_max_over_alpha, "overturned": bool(tr.overturned),
            "overturn_mode": overturn_mode(tr.overturned, before),
            "overturn_time": math.nan if tr.overturn_time is None else float(tr.overturn_time),
            "impacts": tr.impact_count, "uplift": tr.uplifts > 0, "uplifts": tr.uplifts, "u_max": tr.u_max,
            "slide_max": math.nan if tr.slide is None or not tr.slide.size
            else float(abs(tr.slide - tr.slide[0]).max())}


def row_of_failure(error: BaseException) -> dict:
    """The result columns of a run that raised: a row saying so, not a lost chunk."""
    return {"status": "failed", "message": f"{type(error).__name__}: {error}",
            "theta_max_over_alpha": math.nan, "overturned": False, "overturn_mode": NOT_OVERTURNED,
            "overturn_time": math.nan, "impacts": 0, "uplift": False, "uplifts": 0, "u_max": math.nan,
            "slide_max": math.nan}


def rows_to_table(rows: list[dict]):
    import pyarrow as pa  # lazy: pyarrow only where a table is built
    # column by column: a design's 176,440 rows in 0.6 s, where one dict per row took 1.3 s
    return pa.Table.from_pydict({k: [r.get(k) for r in rows] for k in COLUMNS}, schema=schema())


def sort_table(table):
    return table.sort_by([(k, "ascending") for k in SORT_KEYS])
