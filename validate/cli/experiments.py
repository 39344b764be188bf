"""Score the rigid rocking model, MuJoCo and PyBullet against measured shake-table tests of two
granite rocks (overturned or not), beside the data's discrete-element baseline.

`isorock experiments [--data DIR] [--engines …] [--out DIR]` runs study.py and writes
experiments.md (tables), scores.csv, runs.csv, study.json and errors.png through
validate.output (all or none; the folder must be new, empty or an earlier isorock output)."""
from __future__ import annotations

import csv
import math

from ...analytic.errors import InputError
from ..io.provenance import provenance
from ..core.estimate import announce_cost
from ..io.output import Outputs, to_json
from ..io.progress import Progress
from ..tools.experiments import data, fitted, misses, processing, study
from ..tools.experiments.figures import error_figure

DEFAULT_OUT = "isorock-experiments"
DEFAULT_MODEL = "isorock-model.json"


def add_parser(sub) -> None:
    p = sub.add_parser("experiments", help="score the rigid rocking model and the contact engines against "
                                           "measured shake-table tests (overturned or not)",
                       description=__doc__.split("\n\n")[0])
    p.add_argument("--data", default=str(study.default_data()), metavar="DIR",
                   help="the shake-table data folder: results.csv and Shake_Table_Response/TestNNN.txt[.gz] (its "
                        "README; a clone of the original repository is not this layout) (default: %(default)s)")
    p.add_argument("--engines", default="analytic,asymmetric", metavar="E[,E]",
                   help=f"engines to run, comma-separated, from {', '.join(study.ENGINES)} (default: "
                        "%(default)s; mujoco adds about 0.4 s per test, specimen and sign, bullet about 0.7 s)")
    p.add_argument("--steps", default=",".join(processing.DEFAULT_STEPS), metavar="S[,S]",
                   help=f"processing steps of the table acceleration, from {', '.join(processing.STEPS)}, "
                        "or none (default: %(default)s)")
    p.add_argument("--lowpass-hz", type=float, default=processing.LOWPASS_HZ, metavar="HZ",
                   help="the low-pass corner (default: %(default)s)")
    p.add_argument("--tests", metavar="N[,N]", help="only these test numbers (default: every test with a file "
                                                    "and an outcome)")
    p.add_argument("--sensitivity", action="store_true",
                   help="also run the rigid engines (analytic, and asymmetric when it runs) with each processing step "
                        "left out (about 15 s per variant)")
    p.add_argument("--overturning-scale", action="store_true",
                   help="also score the analytic forward block by the record scale (0.5 to 2, 17 scales) at which it "
                        "first overturns, and its threshold following the record's PGV/PGA: the best predictor here "
                        "(about 15 s more per specimen on 2 cores)")
    p.add_argument("--mujoco-friction", type=float, metavar="MU",
                   help="mujoco: table–rock friction coefficient (default 0.5, the data's own simulation's)")
    p.add_argument("--mujoco-dampratio", type=float, metavar="ZETA",
                   help="mujoco: contact damping ratio, solref's second number (default 1: critical)")
    p.add_argument("--bullet-friction", type=float, metavar="MU",
                   help="bullet: table–rock friction coefficient (default 0.5, as mujoco's)")
    p.add_argument("--bullet-restitution", type=float, metavar="E",
                   help="bullet: table–rock restitution, 0 to 1 (default 0.3, the data's own simulation's)")
    p.add_argument("--fit", metavar="DIR", help="fit on the tests of DIR (its layout as --data's; --tests to take "
                   "some): choose the predictor nested in folds grouped by record, fit it on all of them, and write "
                   f"the frozen model file to --out (default: {DEFAULT_MODEL}; a new file)")
    p.add_argument("--predict", metavar="DIR", help="score the tests of DIR (--tests to take some) with the frozen "
                   "--model, refitting nothing; writes prediction.md and prediction.json to --out")
    p.add_argument("--model", metavar="FILE", help="the model file --fit wrote (with --predict)")
    p.add_argument("--misses", nargs="?", const="default", metavar="MU[,MU]",
                   help="what the rigid model misses, test by test (issue 38): the forward block's verdicts beside "
                        "the rock's own two edges and the block sliding on the table at each friction μ (default "
                        + ",".join(f"{m:g}" for m in misses.FRICTIONS) + "); writes misses.csv and misses.md "
                        "into --out (docs/experiments.md)")
    p.add_argument("--out", default=DEFAULT_OUT, metavar="DIR", help="output folder (default: %(default)s); with "
                   "--fit the model file")
    p.set_defaults(func=main)


def _engines(text):
    names = [x.strip() for x in text.split(",") if x.strip()]
    for n in names:
        if n not in study.ENGINES:
            raise InputError(f"engines = {text!r}: {n!r} is not one of {', '.join(study.ENGINES)}")
    if not names:
        raise InputError(f"engines = {text!r}: name at least one of {', '.join(study.ENGINES)}")
    return tuple(dict.fromkeys(names))


def _tests(text):
    if text is None:
        return None
    try:
        tests = [int(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise InputError(f"tests = {text!r}: must be comma-separated test numbers") from None
    if len(set(tests)) < data.MIN_TESTS:  # one test leaves nothing to fit its held-out threshold on
        raise InputError(f"tests = {text!r}: name at least {data.MIN_TESTS} tests (each is scored by a threshold "
                         "fitted on the others)")
    return tests


#: the study's options that --fit and --predict do not take (they run the candidates of
#: experiments.fitted, and the model's own processing when predicting)
STUDY_ONLY = {"engines": "analytic,asymmetric", "sensitivity": False, "overturning_scale": False,
              "mujoco_friction": None, "mujoco_dampratio": None, "bullet_friction": None, "bullet_restitution": None}


def fit_or_predict(a) -> int:
    """`--fit DIR` and `--predict DIR --model FILE` (experiments.fitted)."""
    if a.fit is not None and a.predict is not None:
        raise InputError("fit, predict: give one of them (fit on one set of tests, then predict another)")
    for name, default in STUDY_ONLY.items():
        if getattr(a, name) != default:
            raise InputError(f"{name.replace('_', '-')} = {getattr(a, name)!r}: not taken with --fit or --predict "
                             "(they run experiments.fitted's candidates)")
    if a.data != str(study.default_data()):
        raise InputError(f"data = {a.data!r}: with --fit or --predict the folder is theirs (--fit DIR, --predict DIR)")
    tests = _tests(a.tests)
    if a.fit is not None:
        if a.model is not None:
            raise InputError(f"model = {a.model!r}: is read by --predict; --fit writes its model to --out")
        if a.fit == "":
            raise InputError("fit = '': must be a data folder")
        steps = processing.parse_steps(a.steps)
        processing.check_lowpass(a.lowpass_hz)
        with Outputs() as outputs:
            out = outputs.file("out", DEFAULT_MODEL if a.out == DEFAULT_OUT else a.out, exclusive=True)
            model = fitted.fit(a.fit, tests=tests, steps=steps, lowpass_hz=a.lowpass_hz)
            model["provenance"] = provenance()
            model["fit"]["data"] = str(a.fit)
            out.write_text(to_json(model) + "\n")
            outputs.commit()
        print("\n".join(fit_lines(model)))
        print(f"wrote {out.given}")
        return 0
    if a.model is None:
        raise InputError("model: --predict needs the model file --fit wrote (--model FILE)")
    if a.predict == "":
        raise InputError("predict = '': must be a data folder")
    if a.steps != ",".join(processing.DEFAULT_STEPS) or a.lowpass_hz != processing.LOWPASS_HZ:
        raise InputError("steps, lowpass-hz: --predict uses the model's own processing (frozen by --fit)")
    model = fitted.load_model(a.model)
    with Outputs() as outputs:
        out = outputs.folder("out", a.out)
        result = fitted.predict(a.predict, model, tests=tests)
        result["model"] = str(a.model)
        result["provenance"] = provenance()

        def fill(folder):
            (folder / "prediction.json").write_text(to_json(result) + "\n")
            (folder / "prediction.md").write_text("\n".join(["# isorock experiments: prediction", "",
                                                              *predict_lines(result)]) + "\n")
        out.write(fill)
        outputs.commit()
    print("\n".join(predict_lines(result)))
    print(f"wrote {a.out}/prediction.md, prediction.json")
    return 0


def fit_lines(model) -> list[str]:
    fit = model["fit"]
    lines = [f"fitted on {len(fit['tests'])} tests of {fit['records']} records; {len(fit['candidates'])} candidates "
             f"compared, the choice nested in {fit['outer_folds']} folds grouped by record (inner "
             f"{fit['inner_folds']})", "",
             "| specimen | predictor chosen | nested held-out accuracy [95% CI over records] | chosen per fold | "
             "rigid model's own verdict |", "|---|---|---|---|---|"]
    for s, e in model["specimens"].items():
        n = e["nested"]
        lo, hi = n["accuracy_records_ci"]
        lines.append(f"| SP{s} | {e['predictor']} | {n['accuracy']:.3f} [{lo:.3f}, {hi:.3f}] | "
                     f"{len(set(n['chosen_per_fold']))} different in {len(n['chosen_per_fold'])} | "
                     f"{n['own_verdict_accuracy']:.3f} |")
    return lines


def predict_lines(result) -> list[str]:
    seen = result["seen_in_fit"]
    lines = [f"{len(result['tests'])} tests of {result['records']} records; "
             + (f"**{len(seen)} of them were in the fit** (their score is not held out)" if seen
                else "none of them was in the fit"), "",
             "| specimen | predictor | accuracy [95% CI over tests] | [95% CI over records] | hard tests: accuracy (n) "
             "| never overturned at any scale ≤ 2: accuracy (n) |", "|---|---|---|---|---|---|"]
    for s, r in result["specimens"].items():
        m = r["scores"]
        hard, easy = r["hard"], r["never_overturned"]
        lines.append(f"| SP{s} | {r['predictor']} | {_ci(m, 'accuracy')} | "
                     f"[{r['accuracy_records_ci'][0]:.3f}, {r['accuracy_records_ci'][1]:.3f}] | "
                     f"{'—' if hard is None else format(hard['accuracy'], '.3f')} ({r['hard_tests']}) | "
                     f"{'—' if easy is None else format(easy['accuracy'], '.3f')} ({r['never_overturned_tests']}) |")
    return lines


def _frictions(text: str) -> tuple[float, ...]:
    if text == "default":
        return misses.FRICTIONS
    try:
        return misses.check_frictions(tuple(float(x) for x in text.split(",")))
    except ValueError:
        raise InputError(f"misses = {text!r}: must be comma-separated friction coefficients, e.g. 0.3,0.5,0.8") \
            from None


def run_misses(a) -> int:
    """--misses: the rigid model's misses, test by test (experiments/misses.py), written whole or not at all."""
    if a.fit is not None or a.predict is not None or a.model is not None or a.overturning_scale or a.sensitivity:
        raise InputError("misses: a study of its own; give it without --fit, --predict, --model, "
                         "--overturning-scale and --sensitivity")
    frictions = _frictions(a.misses)
    steps = processing.parse_steps(a.steps)
    processing.check_lowpass(a.lowpass_hz)
    tests = _tests(a.tests)

    def announce(simulated):  # the sliding runs' cost, before their minutes
        announce_cost("experiments --misses", {"analytic": simulated}, budget_s=0, speeds=misses.SLIDING_SPEED,
                      basis="on these records' sliding runs, measured loaded (docs/experiments.md)")
    with Outputs() as outputs:
        out = outputs.folder("out", a.out)
        result = misses.build(a.data, frictions=frictions, tests=tests, steps=steps, lowpass_hz=a.lowpass_hz,
                              announce=announce, progress=lambda n: Progress(n, "sliding runs", enabled=None))
        out.write(lambda folder: misses.write(result, folder))
        outputs.commit()
    print("\n".join(misses.table_lines(result)))
    print(f"wrote {a.out}/misses.md, misses.csv")
    return 0


def main(a) -> int:
    if a.misses is not None:
        return run_misses(a)
    if a.fit is not None or a.predict is not None:
        return fit_or_predict(a)
    if a.model is not None:
        raise InputError(f"model = {a.model!r}: is read by --predict (--predict DIR --model FILE)")
    engines = _engines(a.engines)
    steps = processing.parse_steps(a.steps)
    processing.check_lowpass(a.lowpass_hz)  # up front, not after every test is read
    tests = _tests(a.tests)
    if a.overturning_scale and "analytic" not in engines:
        raise InputError(f"overturning-scale: scores the analytic engine's forward block; engines = {a.engines!r} "
                         "must include analytic")
    contact: dict = {}
    for engine, name, value, allowed in (
            ("mujoco", "friction", a.mujoco_friction, "a positive number"),
            ("mujoco", "dampratio", a.mujoco_dampratio, "a positive number"),
            ("bullet", "friction", a.bullet_friction, "a positive number"),
            ("bullet", "restitution", a.bullet_restitution, "a number from 0 to 1")):
        if value is not None:
            ok = 0 <= value <= 1 if name == "restitution" else value > 0 and math.isfinite(value)
            if not ok:
                raise InputError(f"{engine}-{name} = {value!r}: must be {allowed}")
            contact.setdefault(engine, {})[name] = value
    with Outputs() as outputs:
        out = outputs.folder("out", a.out)  # refused before the runs, not after

        def announce(simulated):  # the hull engines' cost, before their minutes (issue 34)
            announce_cost("experiments", simulated, budget_s=0, speeds=study.HULL_SPEEDS,
                          basis="on this study's hull runs, measured loaded (docs/experiments.md, Cost)")
        result = study.build(a.data, engines=engines, steps=steps, lowpass_hz=a.lowpass_hz, tests=tests,
                             sensitivity=a.sensitivity, contact=contact, overturning_scale=a.overturning_scale,
                             announce=announce)
        result["provenance"] = provenance()
        out.write(lambda folder: write(result, folder))
        outputs.commit()
    print("\n".join(table_lines(result)))
    print(f"wrote {a.out}/experiments.md, scores.csv, runs.csv, study.json, errors.png")
    return 0


def _ci(row, key):
    v, (lo, hi) = row[key], row[key + "_ci"]
    return "—" if v != v else f"{v:.3f} [{lo:.3f}, {hi:.3f}]"


def score_rows(result):
    """(specimen, name, kind, metrics) of every scored row; kind 'own' (nothing fitted) or
    'held-out' (cross-validated)."""
    for s, rows in result["scores"].items():
        for name, row in rows.items():
            for kind, key in (("own", "own"), ("held-out", "cv")):
                if key in row:
                    yield s, name, kind, row[key]


def table_lines(result) -> list[str]:
    lines = ["| specimen | predictor | verdict | accuracy [95% CI] | precision | recall | F1 | ROC AUC |",
             "|---|---|---|---|---|---|---|---|"]
    for s, name, kind, m in score_rows(result):
        lines.append(f"| SP{s} | {name} | {kind} | {_ci(m, 'accuracy')} | {_ci(m, 'precision')} | "
                     f"{_ci(m, 'recall')} | {_ci(m, 'f1')} | {_ci(m, 'auc') if 'auc' in m else '—'} |")
    return lines


def sensitivity_lines(result) -> list[str]:
    rows = result.get("sensitivity")
    if not rows:
        return []
    keys = [k for k in rows[0] if k != "variant"]
    lines = ["| processing | " + " | ".join(keys) + " |", "|---|" + "---|" * len(keys)]
    for r in rows:
        lines.append(f"| {r['variant']} | " + " | ".join(f"{r[k]:.3f}" for k in keys) + " |")
    return lines


def specimen_lines(result) -> list[str]:
    lines = ["| specimen | direction | b (m) | h (m) | R (m) | α (rad) | p (1/s) | block H × B (m) |",
             "|---|---|---|---|---|---|---|---|"]
    for s, d in result["specimens"].items():
        for direction in ("forward", "backward"):
            e = d[direction]
            lines.append(f"| SP{s} | {direction} | {e['b']:.4f} | {e['h']:.4f} | {e['R']:.4f} | {e['alpha']:.4f} | "
                         f"{e['p']:.3f} | {e['block_height']:.4f} × {e['block_width']:.4f} |")
    return lines


def write(result, folder) -> None:
    (folder / "study.json").write_text(to_json(result) + "\n")
    with open(folder / "scores.csv", "w", newline="") as f:
        w = csv.writer(f)
        keys = ["accuracy", "precision", "recall", "f1", "auc"]
        w.writerow(["specimen", "predictor", "verdict"] + [x for k in keys for x in (k, k + "_lo", k + "_hi")]
                   + ["tp", "fp", "fn", "tn"])
        for s, name, kind, m in score_rows(result):
            vals = []
            for k in keys:
                vals += [m.get(k, ""), *(m.get(k + "_ci") or ["", ""])]
            w.writerow([s, name, kind] + vals + [m["tp"], m["fp"], m["fn"], m["tn"]])
    with open(folder / "runs.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["specimen", "engine", "test", "measured", "predicted", "score", "wall_s"])
        for s, engines in result["runs"].items():
            for name, rows in engines.items():
                for t, (pred, score, wall) in rows.items():
                    w.writerow([s, name, t, result["outcomes"][t]["measured"][s], int(pred), score, wall])
    md = ["# isorock experiments", "", f"Tests: {len(result['tests'])}; processing: "
          f"{', '.join(result['steps']) or 'none'} (low-pass {result['lowpass_hz']:g} Hz).", "",
          "## Scores", "", *table_lines(result), "", "## Equivalent blocks", "", *specimen_lines(result), "",
          "## Cost (wall s)", "", *(f"- {k}: {v:.1f} s" for k, v in result["cost"].items())]
    sens = sensitivity_lines(result)
    if sens:
        md += ["", "## Processing sensitivity (accuracy)", "", *sens]
    (folder / "experiments.md").write_text("\n".join(md) + "\n")
    error_figure(result, folder / "errors.png")
