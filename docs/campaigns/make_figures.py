"""The figures of docs/campaigns.md from four campaign folders (run first):

    isorock sweep docs/campaigns/spectrum-analytic.toml  --out sweep-spectrum-analytic
    isorock sweep docs/campaigns/spectrum-contact.toml   --out sweep-spectrum-contact
    isorock sweep examples/fragility.toml                --out sweep-fragility
    isorock sweep docs/campaigns/fragility-contact.toml  --out sweep-fragility-contact
    python docs/campaigns/make_figures.py sweep-spectrum-analytic sweep-spectrum-contact \
        sweep-fragility sweep-fragility-contact docs/images

The spectrum joins the analytic model's fine grid with the contact engines' coarse one;
the fragility figure joins the analytic model over the whole FEMA P695 far-field set
with the contact engines (and the analytic model, relabelled) on the subset.
"""
import sys
from pathlib import Path

import pyarrow as pa
import pyarrow.compute as pc
import pyarrow.parquet as pq

from isorock.campaign.products import (_columns, agreement, agreement_figure, fragility_figure,
                                       fragility_fits, spectrum_figure)


def table(folder):
    return pq.read_table(Path(folder) / "results.parquet")


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
    subset = table(frag_subset)
    is_analytic = pc.equal(subset["engine"], "analytic")
    n_records = len(set(subset["motion"].to_pylist()))
    relabelled = subset.set_column(subset.schema.get_field_index("setting"), "setting",
                                   pc.if_else(is_analytic, f"default, {n_records} records",
                                              subset["setting"]))
    fits = fragility_fits(_columns(pa.concat_tables([table(frag_all), relabelled])))
    fragility_figure(fits, out / "campaign-fragility.png")
    print("| system | engine | setting | records | median PGA θ (g) | 5–95% of θ | dispersion β |")
    print("|---|---|---|---|---|---|---|")
    for f in fits:
        fit = f["fit"]
        print(f"| {f['system']} | {f['engine']} | {f['setting']} | {f['records']} | {fit.median:.3g} | "
              f"{fit.median_band[0]:.3g}–{fit.median_band[1]:.3g} | {fit.dispersion:.3g} | {fit.note}")


if __name__ == "__main__":
    main(*sys.argv[1:6])
