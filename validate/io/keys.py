"""The keys a user gives a System and a ground motion, declared once (issue 35).

Each key is a `Key`: its name (the System's field, the argparse dest and the TOML key
alike), its kind, its unit, its help text and its option's spelling. Every surface is
made from these declarations: `validate`'s and `run`'s options (cli/options.py; their typed
values, io/options.py), a --config file's [system] table and motion keys (io/config_file.py,
through io/schema.field_type), and the element checks of a campaign's grid axes that are the
same keys (campaign/schema.py). A key added here appears in all of them.

Plain data: building a parser imports this without pydantic or NumPy.
"""
from __future__ import annotations

from dataclasses import dataclass

from ...analytic.system import ISOLATOR_KINDS

#: what a key's value may be: a file refuses anything else when it is read (io/schema.field_type);
#: an option takes any number, and the model's own checks say what is allowed
POSITIVE, NON_NEGATIVE, BOOL, CHOICE = "positive", "non-negative", "bool", "choice"
KINDS = (POSITIVE, NON_NEGATIVE, BOOL, CHOICE)

#: a record's acceleration units, as analytic.motion.UNITS names them (written out here, not
#: imported: that module loads NumPy, and building a parser must not; a test holds them equal)
UNITS = ("m/s2", "g", "gal", "cm/s2")
#: a record file's formats, as analytic.motion.FORMATS names them (likewise)
FORMATS = ("at2", "jma", "csv")
#: the words of the engine options that are choices (--cone, --integrator) and of --overturn
CONES = ("pyramidal", "elliptic")
INTEGRATORS = ("Euler", "implicit", "implicitfast", "RK4")
OVERTURN_RULES = ("past-alpha", "alpha")


class Default(float):
    """A number the command filled in, not the user's: a command that takes a statue's mesh
    (--statue) refuses the block's --height and --width given with it, and can tell them apart."""


def given(value) -> bool:
    """Whether an option's value is the user's (not None, not a Default)."""
    return value is not None and not isinstance(value, Default)


@dataclass(frozen=True)
class Key:
    """One key: `name` is the System's field, the argparse dest and the TOML key; `kind` one
    of KINDS (a choice's words in `choices`); `help` the option's text, as --help prints it."""
    name: str
    kind: str
    help: str
    #: the unit of its value, as its help text states it (None: a ratio, a word or a switch)
    unit: str | None = None
    choices: tuple[str, ...] = ()
    #: the option's other spellings (--damping for --damping-ratio)
    aliases: tuple[str, ...] = ()
    metavar: str | None = None
    #: an option a command may require (add_system_options(required=True)): the block itself
    required: bool = False

    def __post_init__(self):
        # a misspelt kind would otherwise surface as a KeyError where a surface is made
        assert self.kind in KINDS, self.kind
        assert (self.kind == CHOICE) == bool(self.choices), self.name

    @property
    def flag(self) -> str:
        """The option: --base-mass for base_mass."""
        return "--" + self.name.replace("_", "-")


def _by_name(*keys: Key) -> dict[str, Key]:
    return {k.name: k for k in keys}


#: the block, its base and a linear isolator, and the statue's friction on its base (add_system_options)
SYSTEM = _by_name(
    Key("height", POSITIVE, "block height H = 2h, m", unit="m", required=True),
    Key("width", POSITIVE, "block width B = 2b, m", unit="m", required=True),
    Key("mass", POSITIVE, "block mass m, kg", unit="kg", required=True),
    Key("base_mass", POSITIVE, "base plate mass m_b, kg (μ = m/m_b)", unit="kg", required=True),
    Key("period", POSITIVE, "isolation period T = 2π√(M/k), s", unit="s"),
    Key("damping_ratio", NON_NEGATIVE, "isolator damping ratio ξ = c/(2Mω), dimensionless (--damping is an alias)",
        aliases=("--damping",)),
    Key("stiffness", POSITIVE, "isolator stiffness k, N/m (instead of --period)", unit="N/m"),
    Key("dashpot", NON_NEGATIVE, "isolator dashpot c, N·s/m (with --stiffness)", unit="N·s/m"),
    Key("fixed_base", BOOL, "fixed (non-isolated) base: μ = 0"),
    # the statue's friction on its base, μ_s and μ_k (docs/sliding.md)
    Key("statue_friction", POSITIVE,
        "Coulomb friction μ_s between the statue and its base (static): the statue may then slide, rock or slide "
        "and rock (docs/sliding.md); omitted: it cannot slip (model.md)", metavar="MU"),
    Key("kinetic_friction", POSITIVE,
        "μ_k while the statue slips, at most --statue-friction (default: --statue-friction)", metavar="MU_K"),
)

#: a non-linear isolator and its parameters (add_isolator_options; docs/isolators.md). Which
#: keys each kind takes is checked where the System is made (io/inputs._isolator_from_args), so
#: a file and the options are refused in the same words
ISOLATOR = _by_name(
    Key("isolator", CHOICE, "the isolator under the base (default: %(default)s; bilinear: --stiffness/--period set "
        "its initial stiffness)", choices=ISOLATOR_KINDS),
    Key("radius", POSITIVE, "friction-pendulum: radius of curvature R_fp, m; ball-in-bowl: its effective radius "
        "R_eff; double-friction-pendulum: R1, surface 1's", unit="m"),
    Key("friction_coefficient", NON_NEGATIVE,
        "friction-pendulum: the slider's friction coefficient μ_f (not --friction, the block–base contact's); "
        "with --friction-rate, μ_min, its value at rest"),
    Key("friction_max", NON_NEGATIVE, "friction-pendulum: μ_max of a velocity-dependent friction "
        "μ_f(v) = μ_max − (μ_max − μ_min)·exp(−a|v|) (with --friction-rate)"),
    Key("friction_rate", NON_NEGATIVE,
        "friction-pendulum: a, s/m, of that velocity-dependent friction (with --friction-max)", unit="s/m"),
    Key("post_yield_ratio", NON_NEGATIVE, "bilinear: post-yield over initial stiffness, in [0, 1)"),
    Key("yield_displacement", POSITIVE, "bilinear: yield displacement u_y, m", unit="m"),
    Key("slope", POSITIVE, "ball-in-cone: the cone's slope tanφ (rise over run), in (0, 1]"),
    Key("rolling_resistance", NON_NEGATIVE,
        "ball-in-cone, ball-in-bowl: the rolling resistance μ_r (a Coulomb friction μ_r·M·g)"),
    Key("radius_2", POSITIVE, "double-friction-pendulum: R2, surface 2's radius, m", unit="m"),
    Key("friction_coefficient_2", NON_NEGATIVE,
        "double-friction-pendulum: μ2, surface 2's friction (--friction-coefficient is μ1)"),
)
#: the options of a non-linear isolator (add_isolator_options), argparse dests
ISOLATOR_KEYS = tuple(k for k in ISOLATOR if k != "isolator")

#: a record's units and format, and the peak it is scaled to (add_motion_options; a --config
#: file's keys of the same names)
MOTION = _by_name(
    Key("format", CHOICE, "record format: at2 (PEER, g), jma (gal), csv (two columns t, a); guessed from the file "
        "when omitted", choices=FORMATS),
    Key("units", CHOICE, "units of a record: required for a two-column (csv) file unless the file states them "
        "('# units: g', or a header 't [s], a [g]'); for an AT2 or JMA file, which state theirs, it must agree",
        choices=UNITS),
    Key("pga", POSITIVE, "scale the motion to this peak ground acceleration, g (instead of --scale)", unit="g",
        metavar="G"),
    Key("pgv", POSITIVE, "scale the motion to this peak ground velocity, m/s (its samples integrated from rest; "
        "instead of --scale)", unit="m/s", metavar="V"),
)
