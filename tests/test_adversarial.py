"""Every hostile input of tests/adversarial_cases.py ends as it should: one error line
and exit 2, or the right result; never a traceback, a hang, or a change to anything in
the working folder but the command's own outputs (issue 13; rounds two, three and four:
issues 24 and 34)."""
import pytest

from adversarial_cases import cases, run_in_process
from adversarial_round_three import VSR

CASES = [c for c in cases() if c.in_process]


@pytest.mark.parametrize("case", CASES, ids=[f"{c.cls}: {c.name}" for c in CASES])
def test_hostile_input(case, tmp_path):
    if "vsr" in case.needs and not (VSR / "models").is_dir():
        pytest.skip(f"shared shake-table data not found at {VSR} (expected beside the repository)")
    d = tmp_path / "work"
    d.mkdir()
    outcome = run_in_process(case, d)
    assert outcome.verdict(case, d) in ("exit 2", "correct result"), (outcome.verdict(case, d), outcome.err)
