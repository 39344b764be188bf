"""The analytic CSV has one row per time: an impact, stored twice at its time (before
and after), keeps the post-impact row."""
import csv

import numpy as np

from isorock.analytic.coefficients import beta
from isorock.analytic.system import System
from isorock.validate.core.engines import get_engine


def test_csv_has_no_duplicate_times_and_keeps_the_post_impact_row(tmp_path):
    system = System.fixed(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0)
    traj = get_engine("analytic").simulate(system, duration=1.5, theta0=0.5 * system.alpha)
    impact_times = [i.t for i in traj.impacts]
    assert impact_times, "free rocking from 0.5α must hit the base within 1.5 s (t₁ ≈ 0.50 s)"
    assert np.any(np.diff(traj.t) == 0), "the stored history repeats impact times (the case the CSV must fold)"

    path = tmp_path / "h.csv"
    traj.to_csv(path)
    rows = list(csv.reader(path.open()))
    assert rows[0] == ["t", "u", "u_dot", "theta", "theta_dot"]
    data = np.array(rows[1:], dtype=float)
    t = data[:, 0]
    assert np.all(np.diff(t) > 0), "CSV times must increase strictly"
    assert t.size == np.unique(traj.t).size

    # at the first impact, |θ̇| in the CSV is the post-impact one: β (closed form) × the pre-impact one
    first = traj.impacts[0]
    row = data[np.argmin(np.abs(t - first.t))]
    pre = traj.theta_dot[np.nonzero(traj.t == first.t)[0][0]]
    expected = beta(system.slenderness, 0.0) * abs(pre)
    assert abs(abs(row[4]) - expected) < 1e-6 * abs(pre)
