"""A plain-text progress bar with ETA.

On a terminal it redraws one line; otherwise (a log file, CI) it prints one
line per finished run, so the output stays readable either way.
"""
import sys
import time


def format_duration(seconds):
    if seconds is None or seconds != seconds or seconds == float("inf"):
        return "--:--"
    seconds = int(round(seconds))
    h, rest = divmod(seconds, 3600)
    m, s = divmod(rest, 60)
    return f"{h}:{m:02d}:{s:02d}" if h else f"{m:02d}:{s:02d}"


class Progress:
    def __init__(self, total, stream=None, width=28, clock=time.monotonic):
        self.total, self.done, self.width = total, 0, width
        self.stream = stream or sys.stdout
        self.tty = bool(getattr(self.stream, "isatty", lambda: False)())
        self.clock = clock
        self.start = clock()
        self.counts = {}

    def eta(self):
        """Remaining time, from the mean wall time per finished run so far."""
        if self.done == 0:
            return None
        elapsed = self.clock() - self.start
        return elapsed / self.done * (self.total - self.done)

    def line(self, last=""):
        frac = self.done / self.total if self.total else 1.0
        filled = int(round(frac * self.width))
        bar = "#" * filled + "." * (self.width - filled)
        elapsed = format_duration(self.clock() - self.start)
        text = (f"[{bar}] {self.done}/{self.total} {100 * frac:3.0f}% "
                f"elapsed {elapsed} eta {format_duration(self.eta())}")
        return f"{text}  {last}" if last else text

    def update(self, row):
        self.done += 1
        failure = row.get("failure", "?")
        self.counts[failure] = self.counts.get(failure, 0) + 1
        last = f"{row.get('problem')} {row.get('solver')} tol={row.get('tol'):g}: {failure}"
        if self.tty:
            self.stream.write("\r\033[K" + self.line(last)[: 160])
            if self.done == self.total:
                self.stream.write("\n")
        else:
            self.stream.write(self.line(last) + "\n")
        self.stream.flush()

    def summary(self):
        parts = ", ".join(f"{v} {k}" for k, v in sorted(self.counts.items(), key=lambda kv: -kv[1]))
        return (f"{self.done} runs in {format_duration(self.clock() - self.start)}"
                + (f": {parts}" if parts else ""))
