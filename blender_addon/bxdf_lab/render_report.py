"""The last render's warnings and errors, kept until the next render of the same kind.

Blender's status bar shows one message at a time and the next one replaces it; a render can have
several warnings (an unsupported node, a light exported approximately, a world colour replaced).
The engine records them here and the Render tab lists them, the Material tab those that name the
material. Every warning string names its material, light or world in quotes ("material 'Red':
..."), which is what the per-material filter looks for.

Kept in Python, not in the .blend: a render's messages describe one run, not the file.
"""

import time
from dataclasses import dataclass, field

# What was rendered: F12 (or bpy.ops.render.render), the viewport's Rendered mode and the Material
# tab's preview. Each kind has its own last report, so that a preview (rendered on every edit)
# never hides the last F12 render's messages; the panels show "render" and "viewport".
KINDS = ("render", "viewport", "preview")


@dataclass
class Report:
    kind: str
    scene: str
    summary: str = ""
    warnings: list = field(default_factory=list)
    errors: list = field(default_factory=list)
    cancelled: bool = False
    finished: float = field(default_factory=time.time)
    # Seconds per phase of a finished render (engine.PHASES), for benchmarks and the curious:
    # where a render's time goes besides the samples.
    timings: dict = field(default_factory=dict)

    def messages(self):
        """[(level, text)]: errors first."""
        return [("ERROR", e) for e in self.errors] + [("WARNING", w) for w in self.warnings]

    def naming(self, name):
        """The messages that name `name` (a material, light or world) in quotes."""
        quoted = f"'{name}'"
        return [(level, text) for level, text in self.messages() if quoted in text]


_last = {}
# How many reports have been recorded: a panel that shows them redraws when it changes
# (ui.redraw_after_new_report).
_recorded = 0


def record(report):
    """Replaces the last report of `report.kind`."""
    global _recorded
    if report.kind not in KINDS:
        raise ValueError(f"render report kind '{report.kind}' is unknown; expected one of {KINDS}")
    _last[report.kind] = report
    _recorded += 1


def recorded():
    """How many reports have been recorded since the add-on was loaded."""
    return _recorded


def last(kind):
    """The last report of `kind`, or None before the first such render."""
    return _last.get(kind)


def clear():
    _last.clear()
