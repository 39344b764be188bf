"""What the rigid model misses, test by test, and whether sliding explains it (issue 38).

    nice -n 10 python docs/scripts/experiments_misses.py [--data DIR] [--friction 0.3,0.5,0.8]
                                                        [--tests 11,13,..] [--out DIR]

The study's first form, kept for the commands written with it: it runs `isorock experiments --misses
MU,… --data DIR --tests … --out DIR` (validate/cli/experiments.py, experiments/misses.py), which
writes DIR/misses.csv and DIR/misses.md and prints the counts. Bad input: exit 2, one line.
"""
from __future__ import annotations

import argparse
import sys

from isorock.validate.tools.experiments import misses, study
from isorock.validate.cli.main import main as isorock


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--data", default=str(study.default_data()))
    p.add_argument("--friction", default=",".join(f"{m:g}" for m in misses.FRICTIONS))
    p.add_argument("--tests", default=None)
    p.add_argument("--out", default="isorock-misses")
    a = p.parse_args(argv)
    return isorock(["experiments", "--misses", a.friction, "--data", a.data, "--out", a.out,
                    *(["--tests", a.tests] if a.tests else [])])


if __name__ == "__main__":
    sys.exit(main())
