"""Where each predictor is wrong: the tests on the plane of scaled PGA × PGV/PGA, marked
right, false alarm (predicted overturned, stood) or miss (predicted standing, overturned),
one panel per predictor and specimen."""
from __future__ import annotations

import numpy as np


def _predictions(result, s):
    """name → held-out predictions (the cross-validated ones where the study has them)."""
    out = {}
    tests = result["tests"]
    for name, runs in result["runs"].get(s, {}).items():
        out[name + " (own)"] = np.array([runs[t][0] for t in tests], bool)
    for name, row in result["scores"][s].items():
        if "held" in row:
            out[name] = np.array(row["held"], bool)
    return out


def error_figure(result, path) -> None:
    import matplotlib  # lazy: matplotlib, for the figure only
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: as matplotlib above
    tests = result["tests"]
    pga = np.array([result["outcomes"][t]["pga"] for t in tests])
    ratio = np.array([result["outcomes"][t]["pgv_over_pga"] for t in tests])
    specs = sorted(result["scores"])
    preds = {s: _predictions(result, s) for s in specs}
    names = sorted(set().union(*[set(p) for p in preds.values()]))
    fig, axes = plt.subplots(len(names), len(specs), figsize=(5 * len(specs), 3.2 * len(names)),
                             squeeze=False, sharex=True, sharey=True)
    for j, s in enumerate(specs):
        y = np.array([result["outcomes"][t]["measured"][s] for t in tests], bool)
        for i, name in enumerate(names):
            ax = axes[i][j]
            p = preds[s].get(name)
            if p is None:
                ax.set_visible(False)
                continue
            ok, fa, miss = p == y, p & ~y, ~p & y
            ax.scatter(pga[ok], ratio[ok], s=8, c="0.75", label="right")
            ax.scatter(pga[fa], ratio[fa], s=18, c="tab:orange", marker="^", label=f"false alarm ({fa.sum()})")
            ax.scatter(pga[miss], ratio[miss], s=18, c="tab:blue", marker="v", label=f"miss ({miss.sum()})")
            ax.set_title(f"SP{s}: {name} — accuracy {ok.mean():.3f}", fontsize=9)
            ax.legend(fontsize=7, loc="upper right")
            if i == len(names) - 1:
                ax.set_xlabel("scaled PGA (g)")
            if j == 0:
                ax.set_ylabel("PGV/PGA (s)")
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)
