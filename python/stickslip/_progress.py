"""The progress bar of long calls (``map``, ``basins``): tqdm when it is
installed, otherwise one line on stderr redrawn in place. The Rust side calls
``update_to(done)`` about ten times a second while the work runs."""

from __future__ import annotations

import sys
import time


class Bar:
    """A bar of ``total`` units named ``what``."""

    def __init__(self, total: int, what: str) -> None:
        self.total = int(total)
        self.what = what
        self.done = 0
        self.started = time.monotonic()
        try:
            from tqdm.auto import tqdm  # type: ignore[import-not-found]
        except ImportError:
            self._tqdm = None
        else:
            self._tqdm = tqdm(total=self.total, desc=what, unit="pt")

    def update_to(self, done: int) -> None:
        """Show ``done`` units finished."""
        done = min(int(done), self.total)
        if done <= self.done:
            return
        if self._tqdm is not None:
            self._tqdm.update(done - self.done)
        else:
            rate = done / max(time.monotonic() - self.started, 1e-9)
            sys.stderr.write(
                f"\r{self.what}: {done}/{self.total} ({100 * done / max(self.total, 1):.0f} %, {rate:.0f}/s)"
            )
            sys.stderr.flush()
        self.done = done

    def close(self) -> None:
        """Finish the bar."""
        if self._tqdm is not None:
            self._tqdm.close()
        elif self.done:
            sys.stderr.write("\n")
            sys.stderr.flush()
