"""The one formatter of a table's cells (io.naming.cell), which the run comparison, the
stress grid and a campaign's summary share: a missing value (None or NaN) is the table's
spelling of "not there", never "nan" or "None"; numbers by the table's format."""
from __future__ import annotations

import math

import numpy as np

from isorock.validate.io.naming import cell


def test_missing_values_are_the_tables_spelling_and_numbers_follow_the_format():
    assert cell(None) == cell(math.nan) == cell(np.float32("nan")) == "–"
    assert cell(None, missing="") == cell(math.nan, missing="") == ""
    assert cell(math.inf) == "inf" and cell(-math.inf, "{:+.3g}") == "-inf"
    assert cell(1.234567) == "1.235" and cell(np.float32(0.5)) == "0.5" and cell(0.01234, "{:+.3g}") == "+0.0123"
    # integers, flags and words as written, not by a float format
    assert cell(12345) == "12345" and cell(np.int64(7)) == "7" and cell(True) == "True" and cell("agree") == "agree"


def test_the_stress_table_and_a_campaign_summary_use_it():
    from isorock.validate.tools.campaign.products import _md_table
    from isorock.validate.tools.stress import markdown
    assert _md_table([{"a": math.nan, "b": 2.0, "c": None}])[-1] == "| – | 2 | – |"
    row = dict(engine="analytic", case="c", verdict="pass", cross="", status="completed", finite=True,
               wall_s=0.5, impacts=3, uplifts=1, overturned=False, theta_max_over_alpha=math.nan,
               theta_peak_over_alpha=0.25, u_max=0.1, energy_residual=None, what="w")
    assert "| analytic | c | pass |  | completed | True | 0.5 | 3 | 1 | False |  | 0.25 | 0.1 |  |  | w |  |  |" \
        in markdown([row])
