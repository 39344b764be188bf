"""The notebook API: `isorock.run(...)`, `isorock.report(...)` (what `isorock validate` makes:
`isorock.validate` is the subpackage), `isorock.sweep(...)` with
keyword arguments, the same validation as the command line, results as objects (and
pandas DataFrames) instead of files and printed tables.

Each keyword is the command's option with dashes as underscores (`base_mass=150`,
`pga=0.5`, `engine="analytic,mujoco:fast"`, `timestep=2.5e-4`); a flag is True or False
(`fixed_base=True`, `quick=True`); a list is given as a list (`motion=[...]` for
validate, `engines=[...]`), a pair or a triple as a tuple (`solref=(0.02, 1)`); a number is any
real number (NumPy's too), never a string. The keywords are read into the command's typed
options (io/options.py: RunOptions, ValidateOptions), the value the command line reads its
parsed arguments into too, and both hand it to the same functions: a value the command refuses
is refused here, as an InputError (a ValueError) with the command's one line, its options
named as keywords.

    import isorock
    tr = isorock.run(engine="analytic", height=0.6, width=0.2, mass=80, base_mass=150,
                     period=2.0, damping_ratio=0.15, motion="sine:amp=0.3,freq=2,cycles=2", pga=0.5)
    tr.theta_max_over_alpha, tr.to_dataframe()

It sits on the command line's floor, above the tools it calls (the campaign's among them, which
only this floor imports), and imports no module of the command line: `isorock validate` and
`isorock.report` call the same functions below it (io/inputs.py, tools/report_config.py,
tools/pair_report.py), never one another (issue 35). Nothing below imports it.
"""
from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

from ...analytic.errors import InputError, import_extra, path_value
from ...analytic.limits import check_workers
from ..core.executor import exit_if_bootstrapping
from ..io.inputs import engine_asked, parse_engines, plan_runs, run_budget, simulate_plan, transverse_asked
from ..io.options import RunOptions, ValidateOptions
from ..io.output import check_folder
from ..io.progress import Progress


def _path(key: str, value, *, optional: bool = True):
    """A path keyword (analytic.errors.path_value, which campaign's design shares)."""
    return path_value(key, value, optional=optional)


def _flag(key: str, value) -> bool:
    if not isinstance(value, bool):
        raise InputError(f"{key} = {value!r}: must be True or False")
    return value


def _keywords(text: str) -> str:
    """A command's line with its options named as this API's keywords: --base-mass → base_mass."""
    return re.sub(r"--([a-z][a-z0-9-]*)", lambda m: m.group(1).replace("-", "_"), text)


def run(**options):
    """One simulation, as `isorock run` runs it: the Trajectory (several engines,
    `engine="analytic,mujoco"`: a dict label → Trajectory, in the order given). Keywords:
    `isorock run`'s options (engine, height, width, mass, base_mass, period, damping_ratio,
    fixed_base, motion, units, scale, pga, pgv, duration, theta0_over_alpha, timestep, …),
    without its output options (json, csv, plot: the Trajectory has to_dataframe() and
    to_csv())."""
    from ..tools.campaign.records import fema_pair as read_pair  # lazy: NumPy; the campaign's record pairs (--pair)
    for key in ("json", "csv", "csv_dt", "plot", "quiet"):
        if key in options:
            raise InputError(f"{key}: an output of the command; isorock.run returns the Trajectory "
                             "(its to_dataframe(), to_csv(), summary())")
    a = RunOptions.from_keywords("run", options)
    try:
        plan, _ = plan_runs(a, parse_engines(engine_asked(a)), read_pair=read_pair)
    except InputError as e:
        raise InputError(_keywords(str(e))) from None
    runs, _ = simulate_plan(plan, a, budget=run_budget(a))  # each run within --budget, as the command's
    return next(iter(runs.values())) if len(runs) == 1 else runs


@dataclass(frozen=True)
class Validation:
    """A validation report's results: `verdict` (the command's last line), `passed`,
    `metrics` (what metrics.json holds), `results` (the report's own object) and
    `checks()` (every check as a DataFrame row)."""

    verdict: str
    passed: bool
    metrics: dict
    results: object

    def checks(self):
        pd = import_extra("pandas", "notebook", "Validation.checks")
        return pd.DataFrame(self.metrics["checks"])


def report(*, out: str | None = None, progress: bool = False, **options) -> Validation:
    """The validation report, as `isorock validate` builds it, returned; written to the
    folder `out` too where one is given (the command's rules: a new or empty folder, or
    an earlier report's). Keywords: `isorock validate`'s options (config, motion (a list),
    engines (a list), quick, duration, pga, pgv, system and engine options)."""
    from ..tools.report_config import report_config  # lazy: each entry point its own modules (matplotlib here)
    from ..tools.report_render import metrics, verdict, write_report
    from ..tools.report_run import build
    out, progress = _path("out", out), _flag("progress", progress)
    a = ValidateOptions.from_keywords("validate", options)
    if out is not None:
        check_folder(out)
    if transverse_asked(a):  # a record pair: the pair's validation (tools/pair_report.py), as the command makes it
        return _pair_report(a, out)
    try:
        config = report_config(a)
    except InputError as e:
        raise InputError(_keywords(str(e))) from None
    bars = []

    def bar(total):
        bars.append(Progress(total, "validate", enabled=None if progress else False))
        return bars[-1]
    results = build(config, progress=bar)
    for b in bars:
        b.close()
    if out is not None:
        write_report(results, out)
    return Validation(verdict(results), not results.failed, metrics(results), results)


def _pair_report(a, out) -> "Validation":
    from ..tools import pair_report  # lazy: each entry point its own modules
    from ..tools.campaign.records import fema_pair as read_pair  # the campaign's record pairs (--pair)
    try:
        metrics, results = pair_report.build(a, **pair_report.pair_inputs(a), read_pair=read_pair)
    except InputError as e:
        raise InputError(_keywords(str(e))) from None
    if out is not None:
        pair_report.write(metrics, out)
    metrics = {k: v for k, v in metrics.items() if k != "figure"}  # what metrics.json holds
    return Validation(metrics["verdict"], not any(c["status"] == "fail" for c in metrics["checks"]), metrics, results)


def sweep(spec, *, out=None, workers: int = 0, scheduler: str | None = None, products: bool = True,
          progress: bool = False):
    """A campaign, as `isorock sweep` runs it: the CampaignResult (`.to_dataframe()`, `.table`
    the pyarrow table, `.out` the folder). `spec`: a TOML file's path; or the campaign as a value,
    a dict of the file's tables as Python's tomllib reads them (checked by the same schema, its
    relative paths from the current folder), or a CampaignSpec already checked. workers = 0 runs
    serially in this process (the default here: a notebook needs nothing more); N > 0
    starts a local Dask cluster of N processes, which a script must call under
    `if __name__ == "__main__":` (said in one line where it is not)."""
    from ..tools.campaign.run import run_campaign  # lazy: each entry point its own modules
    from ..tools.campaign.spec import CampaignSpec, load_spec, parse_spec
    if isinstance(spec, dict):  # the campaign as a value: the file's schema, before any work
        spec = parse_spec(spec, Path.cwd() / "campaign.toml")
    elif not isinstance(spec, CampaignSpec):
        spec = load_spec(_path("spec", spec, optional=False))
    out = _path("out", out)
    products, progress = _flag("products", products), _flag("progress", progress)
    check_workers("workers", workers, serial=True)
    if scheduler is not None and not (isinstance(scheduler, str) and scheduler.strip()):
        raise InputError(f"scheduler = {scheduler!r}: must be a Dask scheduler's address, e.g. 'tcp://host:8786'")
    if workers > 0 or scheduler:
        # in a Dask worker rerunning a script's unguarded top level: stop it quietly; the
        # cluster then fails to start, and the except below says what to do in one line
        exit_if_bootstrapping()
    try:
        return run_campaign(spec, out, workers=workers, scheduler=scheduler, products=products,
                            progress=progress)
    except RuntimeError as e:
        # the workers could not start: in a script without a __main__ guard each one stopped
        # at the check above (said in one line there too)
        if "failed to start" in str(e) and workers > 0:
            raise InputError(f"isorock.sweep: the {workers} worker processes could not start ({e}); in a "
                             "script, call it under `if __name__ == \"__main__\":`, or pass workers=0") from None
        raise

