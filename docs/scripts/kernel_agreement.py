"""The compiled kernel against the SciPy reference on seeded random cases (issue 9's
closing note): θmax/α, counted impacts and overturning, past-α cases included.

    python docs/scripts/kernel_agreement.py [--cases 300] [--seed 9] [--json FILE] [--safe-band N]

--safe-band N adds N cases drawn near the safe region of the one-sine spectrum (blocks
that lean past α and return), which random draws rarely hit.
"""
import argparse
import json
import sys
import time
from pathlib import Path

# the cases and the comparison are test code, kept beside the tests (not in the product)
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests"))
from agreement_cases import compare_paths, random_cases, safe_band_cases  # noqa: E402


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--cases", type=int, default=300)
    p.add_argument("--seed", type=int, default=9)
    p.add_argument("--json", help="write every case's row here")
    p.add_argument("--safe-band", type=int, default=0)
    a = p.parse_args(argv)
    start = time.perf_counter()
    out = compare_paths(random_cases(a.seed, a.cases) + safe_band_cases(a.seed, a.safe_band))
    rows = out.pop("rows")
    out["survived_past_alpha"] = sum(r["past_alpha"] and not r["reference_overturned"] for r in rows)
    out["wall_s"] = round(time.perf_counter() - start, 1)
    print(json.dumps(out, indent=2))
    for r in rows:
        if (r["impacts"] != r["reference_impacts"] or r["overturned"] != r["reference_overturned"]
                or abs(r["theta_max_over_alpha"] - r["reference_theta_max_over_alpha"]) > 1e-6):
            print("differs:", r)
    if a.json:
        with open(a.json, "w") as f:
            json.dump({**out, "rows": rows}, f, indent=1)


if __name__ == "__main__":
    main()
