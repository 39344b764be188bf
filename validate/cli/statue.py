"""`isorock statue FILE --unit mm --mass 80`: what a statue's mesh says about its rocking, verdict
first: the direction it tips first and the table acceleration that tips it, and for that
direction (or `--azimuth`) its two tipping edges (α, R, the inertia about each, p), all from
analytic.shape (issue 36). `--example bust|amphora|obelisk` takes a statue made by code
instead of a file; `--write-mesh FILE.stl` writes its mesh; `--plot FILE.png` draws the uplift
acceleration over every direction (polar); `--motion SPEC` the PGA that overturns it shaken along each
direction (the exact model of its two edges); `--json FILE` ('-': standard output) every number."""
from __future__ import annotations

import math
import sys

from ...analytic import shape
from ...analytic.errors import InputError
from ...analytic.motion import load_motion
from ...analytic.shape import EXAMPLES, UNITS
from .options import number
from ..io import keys
from ..io.output import Outputs, to_json

#: directions on the polar figure and in the JSON's table, one per degree
N_AZIMUTHS = 360


def add_parser(sub) -> None:
    p = sub.add_parser("statue", help="a statue's mesh: the direction it tips first, and its two tipping edges",
                       description=__doc__.split("\n\n")[0].split(": ", 1)[1])
    p.add_argument("file", nargs="?", metavar="FILE", help="the statue's mesh (STL, OBJ, PLY, OFF, GLB), standing "
                   "as it stands on its plinth: z up")
    p.add_argument("--example", choices=EXAMPLES, help="a statue made by code instead of FILE (lengths in m)")
    p.add_argument("--unit", choices=tuple(UNITS), help="FILE's length unit (required with FILE: a mesh file states "
                   "none this reader trusts, so it is never guessed)")
    p.add_argument("--mass", type=number, help="the statue's mass, kg")
    p.add_argument("--density", type=number, help="or its density, kg/m³ (mass = density × the mesh's volume)")
    p.add_argument("--azimuth", type=number, help="the shaking direction, degrees from the mesh's x towards y "
                   "(default: the direction it tips first)")
    p.add_argument("--motion", metavar="SPEC", help="the direction it falls: a record file or a pulse, as run takes "
                   "it, scaled in every direction (one every 10°) to PGA levels from 0.05 to 3.2 g (9%% apart), the "
                   "exact model of the statue's two edges along each on a fixed base: the lowest PGA that overturns it "
                   "per direction, and the worst direction")
    p.add_argument("--format", choices=keys.FORMATS, help="--motion's record format (guessed when omitted)")
    p.add_argument("--units", choices=keys.UNITS,
                   help="units of a two-column --motion record that does not state them")
    p.add_argument("--json", metavar="FILE", help="every number as JSON ('-': standard output)")
    p.add_argument("--plot", metavar="FILE.png", help="the uplift acceleration over every direction, polar (and, "
                   "with --motion, the PGA that overturns it)")
    p.add_argument("--write-mesh", metavar="FILE.stl", help="write the mesh read or made (metres), e.g. an example's")
    p.set_defaults(func=cmd_statue)


def load(a):
    """(the statue at rest, its vertices and faces in m, a label) from the options."""
    names = {"mesh": "FILE", "example": "--example", "unit": "--unit", "mass": "--mass", "density": "--density",
             "source": "its mesh FILE or --example NAME"}
    vertices, faces, label = shape.statue_mesh(mesh=a.file, example=a.example, unit=a.unit, names=names)
    return shape.standing(vertices, faces, mass=a.mass, density=a.density, name=label), vertices, faces, label


def summary(body, azimuth_deg: float | None) -> dict:
    """Every number the command prints, writes and draws."""
    weakest, weakest_g = shape.weakest_direction(body)
    azimuth = shape.shaking_direction(body, azimuth_deg)
    grid = [2 * math.pi * k / N_AZIMUTHS for k in range(N_AZIMUTHS)]
    uplift = [body.along(a).lift_off(1)["accel_g"] for a in grid]  # the forward edge's: the table's polar
    return dict(mass=body.mass, volume=body.checks["volume_m3"], com_height=float(body.com[2]),
                footprint_margin=body.checks["margin_m"],
                tips_first=dict(azimuth_deg=math.degrees(weakest), uplift_g=weakest_g),
                azimuth_deg=math.degrees(azimuth) % 360.0, edges=shape.tipping_edges(body, azimuth),
                uplift_by_azimuth=dict(azimuth_deg=[math.degrees(a) for a in grid], uplift_g=uplift))


def verdict(label: str, s: dict) -> str:
    first, e = s["tips_first"], s["edges"]
    f, b = e["forward"], e["backward"]
    lines = [f"{label}: {s['mass']:.4g} kg, its centre of mass {s['com_height']:.3g} m up. It tips first when the "
             f"table accelerates at {first['uplift_g']:.3g} g, pushing it towards {first['azimuth_deg']:.0f}° "
             f"(from the mesh's x towards y).",
             f"Shaken along {s['azimuth_deg']:.0f}°: forward it lifts at {f['uplift_g']:.3g} g and rocks about an "
             f"edge with α {f['alpha']:.4g} rad, R {f['R']:.4g} m, I_O {f['I_O']:.4g} kg·m², p {f['p']:.4g} rad/s; "
             f"backward at {b['uplift_g']:.3g} g, α {b['alpha']:.4g} rad, R {b['R']:.4g} m, I_O {b['I_O']:.4g} kg·m², "
             f"p {b['p']:.4g} rad/s."]
    if abs(f["alpha"] - b["alpha"]) > 1e-9 * max(f["alpha"], b["alpha"]):
        lines.append("Its two edges differ: `isorock run --statue FILE` and `isorock design --statue FILE` take the "
                     "exact model of both (the analytic engines); validate and the contact engines take the block H × B "
                     "still (issue 36).")
    return "\n".join(lines)


def sweep(body, a) -> dict:
    """analytic.shape.overturning_by_azimuth under --motion, its size said before the runs."""
    motion = load_motion(a.motion, format=a.format, units=a.units)
    if motion.is_zero:
        raise InputError(f"--motion = {a.motion!r}: is zero throughout; it has no peak to scale")
    runs = shape.SWEEP_AZIMUTHS * len(shape.SWEEP_LEVELS)
    print(f"isorock statue: {runs:,} runs of the exact model ({shape.SWEEP_AZIMUTHS} directions × "
          f"{len(shape.SWEEP_LEVELS)} PGA levels, {motion.end_time + 5:.3g} s each): seconds on 2 cores (measured: "
          "1,764 runs of a 155 s record in 2 s)", file=sys.stderr, flush=True)
    return shape.overturning_by_azimuth(body, motion)


def sweep_verdict(d: dict) -> str:
    if d["worst"] is None:
        return (f"Under {d['motion']} scaled up to {d['levels_g'][-1]:.3g} g it overturns in no direction "
                "(the exact model of its two edges along each, fixed base).")
    w = d["worst"]
    falls = sum(p is not None for p in d["overturning_pga_g"])
    return (f"Under {d['motion']} it first overturns at {w['pga_g']:.3g} g, shaken along {w['azimuth_deg']:.0f}° "
            f"(the exact model of its two edges along each of {len(d['azimuth_deg'])} directions, fixed base; it "
            f"overturns by {d['levels_g'][-1]:.3g} g in {falls} of them).")


def polar_plot(s: dict, label: str, path) -> None:
    import matplotlib  # lazy: matplotlib only with --plot
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: as matplotlib above
    grid = s["uplift_by_azimuth"]
    theta = [math.radians(a) for a in grid["azimuth_deg"]] + [0.0]
    r = grid["uplift_g"] + grid["uplift_g"][:1]
    fig = plt.figure(figsize=(5.5, 5.5))
    ax = fig.add_subplot(projection="polar")
    ax.plot(theta, r, color="C0")
    first = s["tips_first"]
    ax.plot([math.radians(first["azimuth_deg"])], [first["uplift_g"]], "o", color="C3",
            label=f"tips first: {first['uplift_g']:.3g} g towards {first['azimuth_deg']:.0f}°")
    sweep = s.get("overturning_by_azimuth")
    title = "the table acceleration (g) that tips it, by the direction it pushes it"
    if sweep is not None:
        pairs = [(math.radians(a), p) for a, p in zip(sweep["azimuth_deg"], sweep["overturning_pga_g"])
                 if p is not None]
        if pairs:
            ax.plot([a for a, _ in pairs], [p for _, p in pairs], "s", color="C1", ms=4,
                    label="the PGA that overturns it, shaken along that direction")
        title += f";\nand under {sweep['motion']}, the PGA that overturns it"
    ax.set_rmin(0.0)
    ax.set_title(f"{label}\n{title}", fontsize=9)
    ax.legend(loc="lower center", bbox_to_anchor=(0.5, -0.15), fontsize=8, frameon=False)
    fig.savefig(path, dpi=120, bbox_inches="tight", format="png")
    plt.close(fig)


def cmd_statue(a) -> int:
    with Outputs() as outputs:
        json_out = outputs.file("json", a.json) if a.json is not None else None
        plot_out = outputs.file("plot", a.plot) if a.plot is not None else None
        mesh_out = outputs.file("write-mesh", a.write_mesh) if a.write_mesh is not None else None
        for name in ("units", "format"):
            if getattr(a, name) is not None and a.motion is None:
                raise InputError(f"--{name} = {getattr(a, name)!r}: needs --motion (the record it describes)")
        body, vertices, faces, label = load(a)
        s = summary(body, a.azimuth)
        text = verdict(label, s)
        if a.motion is not None:
            s["overturning_by_azimuth"] = sweep(body, a)
            text += "\n" + sweep_verdict(s["overturning_by_azimuth"])
        if json_out:
            json_out.write_text(to_json(dict(s, statue=label, verdict=text)) + "\n")
        if plot_out:
            plot_out.write(lambda tmp: polar_plot(s, label, tmp))
        if mesh_out:
            import trimesh  # lazy: an optional extra
            mesh = trimesh.Trimesh(vertices, faces, process=False)
            mesh_out.write(lambda tmp: mesh.export(tmp, file_type="stl"))
        outputs.commit()
    print(text, file=sys.stdout if a.json != "-" else sys.stderr)
    return 0
