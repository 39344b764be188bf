"""One progress bar with an ETA, on stderr and only on a terminal: long commands show how
far they are without mixing anything into stdout or into a log a script reads."""
from __future__ import annotations

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
