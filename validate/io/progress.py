"""The one progress bar of every long command (validate, atlas, stress, calibrate, sweep),
drawn by tqdm on stderr, never on stdout: a command's output and a log a script reads stay
clean. On a terminal it is redrawn in place; elsewhere it is silent unless the command
asks for it (`sweep`, whose runs last hours, writes a line every `every` seconds to its
log). It counts units (runs); its ETA follows `work`, the units' expected cost, where the
caller knows it (a campaign's contact runs cost 10⁴ times its analytic ones), else the
count."""
from __future__ import annotations

import math
import sys
import time

#: the share of the expected work done before a Progress gives an ETA: below it the rate
#: says nothing yet (a campaign's first analytic batches are mostly a cluster's start)
ETA_AFTER = 1e-3


class Progress:
    """update(n, work, note) after each finished piece; close() at the end (or use it as a
    context manager). `enabled`: None draws on a terminal only; True also writes lines to a
    log; False draws nothing."""

    def __init__(self, total: int, label: str = "", *, unit: str = "runs", work: float | None = None,
                 stream=None, enabled: bool | None = None, every: float = 10.0):
        from tqdm import tqdm  # lazy: tqdm only where a bar is drawn
        self.stream = stream if stream is not None else sys.stderr
        self.total, self.label, self.unit, self.done = max(int(total), 0), label, unit, 0
        self.work, self.work_done = work, 0.0
        tty = hasattr(self.stream, "isatty") and self.stream.isatty()
        self.enabled = (tty if enabled is None else enabled) and self.total > 0
        self.start = time.monotonic()
        self.bar = tqdm(total=self.total, file=self.stream, disable=not self.enabled, leave=True,
                        mininterval=0.2 if tty else every, miniters=1, dynamic_ncols=tty, ascii=not tty,
                        bar_format="{percentage:3.0f}%|{bar:24}| {desc}")
        if self.enabled:
            self.bar.set_description_str(self._postfix(""), refresh=False)

    @property
    def eta(self) -> float:
        """Seconds left at the rate so far (NaN until ETA_AFTER of the work is done)."""
        elapsed = time.monotonic() - self.start
        frac = self.done / self.total if self.total else 1.0
        ahead = min(1.0, self.work_done / self.work) if self.work else frac
        return elapsed * (1 - ahead) / ahead if ahead >= ETA_AFTER else math.nan

    def _postfix(self, note: str) -> str:
        """What follows the bar: the label, the count, the time so far, the ETA, a note."""
        eta = self.eta
        elapsed = time.monotonic() - self.start
        eta_text = f"{eta:5.0f}" if math.isfinite(eta) else "    ?"
        text = f"{self.label} {self.done}/{self.total} {self.unit}, {elapsed:.0f} s elapsed, ETA {eta_text} s"
        return f"{text} {note}".strip()

    def update(self, n: int = 1, work: float = 0.0, note: str = "") -> None:
        self.done = min(self.total, self.done + n)
        self.work_done += work
        if self.enabled:
            self.bar.set_description_str(self._postfix(note), refresh=False)
            self.bar.update(n)

    def close(self) -> None:
        self.bar.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False


class Silent:
    """The bar of a tool run without one: update and close do nothing."""

    total = done = 0

    def update(self, n: int = 1, work: float = 0.0, note: str = "") -> None:
        pass

    def close(self) -> None:
        pass


def bar_of(progress, total: int, work: float | None = None):
    """The one way a tool shows progress: it is given `progress`, a factory total → bar
    (a Progress, made by the command line once the tool knows its count of runs, or
    anything with update(n, work, note)), or None; this is that bar, or a Silent one.
    `work`: the runs' expected cost, for a factory that takes it (the ETA of a campaign,
    whose contact runs cost 10⁴ times its analytic ones, follows it)."""
    if progress is None:
        return Silent()
    return progress(total) if work is None else progress(total, work=work)


def logged(total: int, work: float | None = None, label: str = "") -> Progress:
    """A bar that also writes a line every 10 s where stderr is a log, not a terminal: a
    campaign's (`isorock sweep` lasts hours, and its log is how one follows it)."""
    return Progress(total, label, work=work, enabled=True)


__all__ = ["Progress", "Silent", "bar_of", "logged", "ETA_AFTER"]
