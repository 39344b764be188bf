"""One progress bar with an ETA, on stderr and only on a terminal: long commands show how
far they are without mixing anything into stdout or into a log a script reads."""
from __future__ import annotations

import math
import sys
import time


class ProgressBar:
    """`advance(n)` after each finished unit of work; `close()` at the end. Silent when
    stderr is not a terminal (or `enabled` is False). The ETA assumes the remaining units
    cost what the finished ones did on average."""

    WIDTH = 28
    INTERVAL = 0.2  # s between redraws

    def __init__(self, total: int, label: str = "", *, enabled: bool | None = None, stream=None):
        self.stream = stream or sys.stderr
        self.total, self.label, self.done = max(int(total), 0), label, 0
        self.enabled = (self.stream.isatty() if enabled is None else enabled) and self.total > 0
        self.start = self.last = time.perf_counter()

    def advance(self, n: int = 1, note: str = "") -> None:
        self.done = min(self.total, self.done + n)
        now = time.perf_counter()
        if self.enabled and (now - self.last >= self.INTERVAL or self.done == self.total):
            self.last = now
            self.stream.write("\r" + self.line(now, note))
            self.stream.flush()

    def line(self, now: float | None = None, note: str = "") -> str:
        now = time.perf_counter() if now is None else now
        elapsed = now - self.start
        fill = int(self.WIDTH * self.done / self.total) if self.total else self.WIDTH
        eta = elapsed / self.done * (self.total - self.done) if self.done else float("nan")
        eta_text = "ETA --" if eta != eta else f"ETA {_duration(eta)}"
        return (f"{self.label} [{'#' * fill}{'.' * (self.WIDTH - fill)}] {self.done}/{self.total} "
                f"{_duration(elapsed)} elapsed, {eta_text} {note}")[:150].ljust(80)

    def close(self) -> None:
        if self.enabled:
            self.stream.write("\n")
            self.stream.flush()


def _duration(seconds: float) -> str:
    seconds = int(round(seconds))
    return f"{seconds // 60}:{seconds % 60:02d}" if seconds >= 60 else f"{seconds} s"


__all__ = ["ProgressBar"]


#: the share of the expected work done before a Progress gives an ETA
ETA_AFTER = 1e-3


class Progress:
    """One progress bar with an ETA on stderr: redrawn in place on a terminal, else a
    line at most every `every` seconds (logs stay short). It counts runs; the ETA follows
    `work` (the tasks' expected cost, `update`'s second argument) where given, else the
    run count."""

    def __init__(self, total: int, *, work: float | None = None, stream=None, every: float = 10.0,
                 label: str = "runs"):
        self.total, self.done, self.label = total, 0, label
        self.work, self.work_done = work, 0.0
        self.stream = stream if stream is not None else sys.stderr
        self.tty = hasattr(self.stream, "isatty") and self.stream.isatty()
        self.every, self.start, self.last = every, time.monotonic(), -math.inf

    def update(self, n: int, work: float = 0.0) -> None:
        self.done += n
        self.work_done += work
        now = time.monotonic()
        if self.tty or now - self.last >= self.every or self.done >= self.total:
            self.last = now
            self._draw(now)

    def _draw(self, now):
        elapsed = now - self.start
        frac = self.done / self.total if self.total else 1.0
        ahead = min(1.0, self.work_done / self.work) if self.work else frac
        # below a thousandth of the work done (a campaign's analytic batches, say, whose
        # seconds are mostly the cluster's start) the rate says nothing yet: "?"
        eta = elapsed * (1 - ahead) / ahead if ahead >= ETA_AFTER else math.nan
        eta_s = f"{eta:5.0f} s" if math.isfinite(eta) else "    ? s"
        if self.tty:
            bar = "#" * int(30 * frac)
            self.stream.write(f"\r[{bar:<30}] {self.done}/{self.total} {self.label} "
                              f"{elapsed:5.0f} s, ETA {eta_s}")
            if self.done >= self.total:
                self.stream.write("\n")
        else:
            self.stream.write(f"{self.done}/{self.total} {self.label} ({100 * frac:.0f}%), "
                              f"{elapsed:.0f} s, ETA {eta_s}\n")
        self.stream.flush()
