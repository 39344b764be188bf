"""What the rigid model misses, test by test, and whether sliding explains it (issue 38).

    nice -n 10 python docs/scripts/experiments_misses.py [--data DIR] [--friction 0.3,0.5,0.8]
                                                        [--tests 11,13,..] [--out DIR]

Writes DIR/misses.csv (every specimen × test: measured, the rigid forward block's own verdict,
the rock's own two edges ±x, the forward block with friction at each μ and how far it slid) and
DIR/misses.md (the counts: experiments/misses.py), and prints the counts. Bad input: exit 2, one line.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

from isorock.analytic.errors import InputError
from isorock.experiments import misses, study


def _floats(text):
    try:
        return tuple(float(x) for x in text.split(","))
    except ValueError:
        raise InputError(f"friction = {text!r}: comma-separated numbers, e.g. 0.3,0.5,0.8") from None


def _ints(text):
    try:
        return [int(x) for x in text.split(",")]
    except ValueError:
        raise InputError(f"tests = {text!r}: comma-separated test numbers, e.g. 11,13,15") from None


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--data", default=str(study.default_data()))
    p.add_argument("--friction", default=",".join(f"{m:g}" for m in misses.FRICTIONS))
    p.add_argument("--tests", default=None)
    p.add_argument("--out", default="isorock-misses")
    a = p.parse_args(argv)
    try:
        frictions = misses.check_frictions(_floats(a.friction))
        tests = _ints(a.tests) if a.tests else None
        result = misses.build(a.data, frictions=frictions, tests=tests)
    except InputError as e:
        print(f"experiments_misses: {e}", file=sys.stderr)
        return 2
    misses.write(result, Path(a.out))
    print("\n".join(misses.table_lines(result)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
