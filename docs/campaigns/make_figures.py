"""The figures of docs/campaigns.md from four campaign folders (run first):

    isorock sweep docs/campaigns/spectrum-analytic.toml  --out sweep-spectrum-analytic
    isorock sweep docs/campaigns/spectrum-contact.toml   --out sweep-spectrum-contact
    isorock sweep examples/fragility.toml                --out sweep-fragility
    isorock sweep docs/campaigns/fragility-contact.toml  --out sweep-fragility-contact
    python docs/campaigns/make_figures.py sweep-spectrum-analytic sweep-spectrum-contact \
        sweep-fragility sweep-fragility-contact docs/images

The spectrum joins the analytic model's fine grid with the contact engines' coarse one;
the fragility figure joins the analytic model over the FEMA P695 far-field set at 15
levels with every engine on the same set at the contact campaign's 5 levels.
"""
import sys
from pathlib import Path

import pyarrow as pa
import pyarrow.compute as pc
import pyarrow.parquet as pq

from isorock.validate.tools.campaign.products import (_columns, agreement, agreement_figure, fragility_figure,
                                       fragility_fits, spectrum_figure)


def table(folder):
    return pq.read_table(Path(folder) / "results.parquet")


def _labelled(t):
    """The analytic rows' setting column as 'default, R records × L levels'."""
    grid = f"{len(set(t['motion'].to_pylist()))} records × {len(set(t['intensity'].to_pylist()))} levels"
    return t.set_column(t.schema.get_field_index("setting"), "setting",
                        pc.if_else(pc.equal(t["engine"], "analytic"), f"default, {grid}", t["setting"]))


def main(spec_fine, spec_coarse, frag_all, frag_subset, out):
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    coarse = table(spec_coarse)
    contact_rows = coarse.filter(pc.invert(pc.equal(coarse["engine"], "analytic")))
    print(spectrum_figure(_columns(pa.concat_tables([table(spec_fine), contact_rows])),
                          out / "campaign-spectrum.png"))
    maps = agreement(_columns(coarse), "frequency_ratio", "amplitude_ratio")
    agreement_figure(maps, out / "campaign-agreement.png")
    for m in maps:
        print({k: m[k] for k in ("engine", "setting", "cases", "verdict_differs", "both_survive",
                                 "theta_departs", "tolerance")})
    # the analytic model on two grids (every level of the fine one; the contact engines'
    # cases): each labelled by its records × levels so the two fits stay apart
    frag_fine, frag_coarse = (_labelled(table(f)) for f in (frag_all, frag_subset))
    fits = fragility_fits(_columns(pa.concat_tables([frag_fine, frag_coarse])))
    fragility_figure(fits, out / "campaign-fragility.png")
    print("| system | engine | setting | records × levels | overturned | median PGA θ (g) | 5–95% of θ | dispersion β |")
    print("|---|---|---|---|---|---|---|---|")
    for f in fits:
        fit = f["fit"]
        over = f"{f['fraction'].mean():.3f}"
        print(f"| {f['system']} | {f['engine']} | {f['setting']} | {f['records']} × {f['levels'].size} | {over} | "
              f"{fit.median:.3g} | {fit.median_band[0]:.3g}–{fit.median_band[1]:.3g} | {fit.dispersion:.3g} | "
              f"{fit.note}")


if __name__ == "__main__":
    main(*sys.argv[1:6])
