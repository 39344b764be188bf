"""`isorock presets [ENGINE] [--json]`: every engine's named presets (ENGINE:PRESET on the
command line), each with its one-line reason and its settings. The reasons are each engine
package's own (`ENGINE.presets`, analytic.engine_protocol.Preset), so this listing and the
engines cannot disagree."""
from __future__ import annotations

import sys
import textwrap

from ...analytic.errors import InputError
from ..core.engines import ALIASES, DISTINCT_ENGINES, get_engine, presets_of
from ..io.output import to_json


def add_parser(sub) -> None:
    p = sub.add_parser("presets", help="every engine's presets, with their reasons and settings",
                       description=__doc__.split("\n\n")[0].split(": ", 1)[1])
    p.add_argument("engine", nargs="?", metavar="ENGINE",
                   help=f"one engine ({', '.join(DISTINCT_ENGINES)}; default: all of them)")
    p.add_argument("--json", action="store_true",
                   help="as JSON: engine → preset → reason, settings (every one), differs (from the default)")
    p.set_defaults(func=cmd_presets)


def _value(v) -> str:
    if isinstance(v, float):
        return f"{v:g}"
    if isinstance(v, (tuple, list)):
        return "(" + ", ".join(_value(x) for x in v) + ")"
    return str(v)


def _settings_line(entry: dict, *, default: bool) -> str:
    keys = list(entry["settings"]) if default else entry["differs"]
    if not keys:
        return "the default's settings"
    text = " ".join(f"{k}={_value(entry['settings'][k])}" for k in keys)
    return text if default else "as default, but " + text


def listing(table: dict) -> str:
    """The text form: per engine, each preset's name and reason, then its settings (the
    default's all, another's those that differ from the default)."""
    lines = []
    for engine, presets in table.items():
        if "unavailable" in presets:  # an engine that cannot be loaded here says why
            lines += [presets["unavailable"], ""]
            continue
        lines.append(f"{engine}  ({len(presets)} presets; use as --engine {engine}:PRESET)")
        width = max(len(n) for n in presets) + 2
        for name, entry in presets.items():
            pad = " " * (2 + width)
            lines.append(f"  {name:<{width}}{entry['reason']}")
            lines += textwrap.wrap(_settings_line(entry, default=name == "default"), 100,
                                   initial_indent=pad, subsequent_indent=pad + "  ")
        lines.append("")
    return "\n".join(lines).rstrip() + "\n"


def cmd_presets(a) -> int:
    if a.engine is not None:
        get_engine(a.engine)  # an unknown name: one line, exit 2
        table = {ALIASES.get(a.engine, a.engine): presets_of(a.engine)}
    else:
        table = {}
        for name in DISTINCT_ENGINES:
            try:
                table[name] = presets_of(name)
            except InputError as e:  # an optional engine not installed here is listed with what to do
                table[name] = {"unavailable": str(e)}
    if a.json:
        print(to_json(table))
    else:
        sys.stdout.write(listing(table))
    return 0
