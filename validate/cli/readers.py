"""What the command line reads beside its options: a motion (io.inputs.motion_from_args) with
--pair read from the campaign's records, which only the command line's floor may import.
The commands that read a motion import it from here; building the parser does not (cli/options.py)."""
from __future__ import annotations

from ..io import inputs
# --pair SUITE:ID → its two horizontal components: the reader the command line hands io.inputs
from ..tools.campaign.records import fema_pair as read_pair


def motion_from_args(a):
    """The motion the options describe (io.inputs.motion_from_args, --pair read by read_pair)."""
    return inputs.motion_from_args(a, read_pair=read_pair)
