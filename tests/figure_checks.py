"""Checks of a rendered figure (issue 25: figures that read at any size): its size in
pixels and whether any two of its texts overlap, measured on the rendered text boxes
(matplotlib's own extents after drawing), not on the code that placed them."""
from __future__ import annotations

import itertools


def rendered_texts(fig):
    """(text, box in pixels) of every non-empty text the figure draws: titles, axis
    labels, tick labels, legend entries, annotations, colorbar labels. Recorded as they
    are drawn (a tick label beyond the axis limits exists but is not drawn)."""
    from unittest import mock

    from matplotlib.text import Text
    drawn = []
    original = Text.draw

    def recording(self, renderer):
        result = original(self, renderer)
        if self.get_text().strip():
            box = Text.get_window_extent(self, renderer)  # an annotation's text, without its arrow
            if box.width > 0 and box.height > 0:
                drawn.append((self.get_text(), box))
        return result
    with mock.patch.object(Text, "draw", recording):
        fig.canvas.draw()
    return drawn


def overlapping_texts(fig, *, slack_px: float = 1.0) -> list[tuple[str, str]]:
    """Pairs of texts whose boxes overlap by more than slack_px in both directions."""
    texts = rendered_texts(fig)
    bad = []
    for (a, ba), (b, bb) in itertools.combinations(texts, 2):
        dx = min(ba.x1, bb.x1) - max(ba.x0, bb.x0)
        dy = min(ba.y1, bb.y1) - max(ba.y0, bb.y0)
        if dx > slack_px and dy > slack_px:
            bad.append((a, b))
    return bad


def texts_outside(fig) -> list[str]:
    """Texts that reach outside the figure (cut off when saved)."""
    w, h = fig.canvas.get_width_height()
    return [t for t, b in rendered_texts(fig) if b.x0 < -1 or b.y0 < -1 or b.x1 > w + 1 or b.y1 > h + 1]


def size_px(fig, dpi: float) -> tuple[int, int]:
    w, h = fig.get_size_inches()
    return round(w * dpi), round(h * dpi)
