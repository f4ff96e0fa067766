"""Compare Renders: the user's scene rendered with BXDF_LAB, CYCLES and POVRAY_RENDER at a preview
resolution and sample count, into a folder the user chose, then shown side by side with labels, a
heat map of BxDF Lab against Cycles, the numbers, and an HTML report.

A CompareRun is a list of steps, one per engine. Each step applies the engine's fair settings
(reference/renderers.md) and the preview size, renders to <folder>/<engine>.exr, and restores
every setting it changed; add-ons an engine needs (POV-Ray's) are enabled for the run only. The
operator (operators/compare_renders.py) runs the steps as render jobs from a modal loop, so the UI
stays live, with progress and Esc; headless it runs them one after the other.

Each material gets a pairing label per engine, following what each engine renders: a material
BxDF Lab renders from its node tree is labelled by the translation of its nodes; one rendered from
its BxDF Lab model is "exact" or "approximate" as its Set Up operator said, or "unsupported" with
the reason (no set-up, or Cycles rendering a node tree of its own).
"""

import html
import math
import os
import time
from dataclasses import dataclass, field

import addon_utils
import bpy
import numpy as np

from . import engine, material_source, nodes

ENGINES = ("BXDF_LAB", "CYCLES", "POVRAY_RENDER")
ENGINE_NAMES = {"BXDF_LAB": "BxDF Lab", "CYCLES": "Cycles", "POVRAY_RENDER": "POV-Ray"}
ENGINE_ADDONS = {"POVRAY_RENDER": "render_povray"}
RESULT_IMAGE = "BxDF Lab comparison"

# The last finished run ({"folder", "report", "figure", "messages"}), for the Render tab's
# "Open Report" button.
last_result = {}


@dataclass
class Options:
    folder: str
    size: int = 256        # longest side of every render, pixels
    samples: int = 32      # BxDF Lab and Cycles samples per pixel


@dataclass
class EngineResult:
    engine: str
    ok: bool = False
    message: str = ""
    path: str = ""
    seconds: float = 0.0


def preview_percentage(scene, size):
    """The resolution percentage that makes the longest side at most `size` pixels."""
    longest = max(scene.render.resolution_x, scene.render.resolution_y)
    return max(1, min(100, int(math.floor(100.0 * size / longest))))


def engine_settings(scene, engine_id, options):
    """(owner, attribute, value) triples that an engine's render sets, all restored after it."""
    r = scene.render
    pairs = [(r, "engine", engine_id), (r, "filepath", r.filepath),
             (r, "resolution_percentage", preview_percentage(scene, options.size)),
             (r.image_settings, "file_format", "OPEN_EXR"), (r.image_settings, "color_depth", "32"),
             (scene.view_settings, "view_transform", "Standard"), (scene.view_settings, "look", "None"),
             (scene.view_settings, "exposure", 0.0), (scene.view_settings, "gamma", 1.0),
             (r, "film_transparent", False)]
    if engine_id == "BXDF_LAB":
        pairs.append((scene.bxdf_lab_render, "samples", options.samples))
    if engine_id == "CYCLES":
        c = scene.cycles
        pairs += [(c, "use_denoising", False), (c, "use_adaptive_sampling", False),
                  (c, "sample_clamp_direct", 0.0), (c, "sample_clamp_indirect", 0.0),
                  (c, "blur_glossy", 0.0), (c, "light_sampling_threshold", 0.0),
                  (c, "samples", options.samples),
                  (c, "max_bounces", scene.bxdf_lab_render.max_bounces)]
    if engine_id == "POVRAY_RENDER":
        # 16-bit sRGB PNG: render_povray loads POV's PNG as sRGB into the linear render result
        # (a linear PNG, File_Gamma=1.0, would be decoded twice).
        pairs += [(scene.pov, "radio_enable", False),
                  (scene.pov, "command_line_switches", "+FN16")]
    use_nodes = engine_id == "CYCLES"
    pairs += [(m, "use_nodes", use_nodes) for m in bpy.data.materials
              if engine_id != "BXDF_LAB" and (m.node_tree is not None or not use_nodes)]
    return pairs


def apply_settings(pairs):
    """Sets the triples; returns what restore_settings needs to undo them."""
    saved = []
    for owner, attr, value in pairs:
        if owner is not None and hasattr(owner, attr):
            saved.append((owner, attr, getattr(owner, attr)))
            setattr(owner, attr, value)
    return saved


def restore_settings(saved):
    for owner, attr, value in reversed(saved):
        setattr(owner, attr, value)


class AddonsForRun:
    """Enables the add-ons the run's engines need, and disables afterwards those it enabled."""

    def __init__(self):
        self.enabled = []

    def need(self, engine_id):
        module = ENGINE_ADDONS.get(engine_id)
        if module is None:
            return True
        loaded, enabled = addon_utils.check(module)
        if not enabled:
            # default_set: render_povray reads its own entry in preferences.addons
            if addon_utils.enable(module, default_set=True, handle_error=None) is None:
                return False
            self.enabled.append(module)
        return True

    def restore(self):
        for module in reversed(self.enabled):
            addon_utils.disable(module, default_set=True)
        self.enabled.clear()


def available_engines():
    return {e.bl_idname for e in bpy.types.RenderEngine.__subclasses__()} | {"CYCLES"}


# ---- pairing labels ----------------------------------------------------------------------

def scene_materials(scene):
    seen = []
    for obj in scene.objects:
        for slot in getattr(obj, "material_slots", ()):
            if slot.material is not None and slot.material not in seen:
                seen.append(slot.material)
    return seen


def _node_pairing(nodes_coverage):
    """(label, why) of a material BxDF Lab renders from its node tree, as Cycles does: the worst
    status of its nodes."""
    statuses = {n["status"] for n in nodes_coverage}
    label = ("unsupported" if "unsupported" in statuses else
             "approximate" if "approximate" in statuses else "exact")
    notes = [f"{n['node']}: {n['why']}" for n in nodes_coverage if n["status"] != "exact"]
    return label, "both render its node tree" + (f" ({'; '.join(notes)})" if notes else "")


def cycles_pairing(material):
    """(label, why) of this material's BxDF Lab render against Cycles', following what each
    renders: Cycles its node tree (engine_settings turns use_nodes on), BxDF Lab the node tree or
    the panel's model (material_source)."""
    if material_source.source(material) == "NODES":
        return _node_pairing(nodes.material_coverage(material))
    settings = material.bxdf_lab
    if settings.cycles_label and material.node_tree is not None:
        return settings.cycles_label, settings.cycles_mapping
    if material.node_tree is not None:
        return "unsupported", ("Cycles renders the material's own node tree; BxDF Lab renders the "
                               f"panel's model ({settings.model}). Use Set Up Cycles Material to "
                               "pair them, or switch the material to its Node Tree")
    return "unsupported", ("no node tree: Cycles renders its default surface; "
                           "use Set Up Cycles Material")


def pov_pairing(material):
    settings = material.bxdf_lab
    if settings.pov_label:
        return settings.pov_label, settings.pov_mapping
    return "unsupported", "no POV-Ray finish set up from the model; use Set Up POV-Ray Material"


def coverage(material):
    """[{"node", "type", "status": exact|approximate|unsupported, "why"}]: how each node of the
    material's tree reaches BxDF Lab. A material rendered from its model translates no node: its
    tree is one entry (every node, one reason), labelled by Set Up Cycles Material when that built
    it, else not rendered by BxDF Lab."""
    if material_source.source(material) == "NODES":
        return nodes.material_coverage(material)
    if material.node_tree is None:
        return []
    settings = material.bxdf_lab
    tree = {"node": ", ".join(n.name for n in material.node_tree.nodes),
            "type": ", ".join(n.bl_idname for n in material.node_tree.nodes)}
    if settings.cycles_label:
        return [dict(tree, status=settings.cycles_label,
                     why=f"built from the panel's model by Set Up Cycles Material: {settings.cycles_mapping}")]
    return [dict(tree, status="unsupported",
                 why=f"not rendered by BxDF Lab: it renders the panel's model ({settings.model})")]


def pairings(scene):
    """[{"material", "model", "CYCLES": (label, why), "POVRAY_RENDER": (label, why),
    "coverage": [...]}]."""
    return [{"material": m.name, "model": m.bxdf_lab.model, "CYCLES": cycles_pairing(m),
             "POVRAY_RENDER": pov_pairing(m), "coverage": coverage(m)}
            for m in scene_materials(scene)]


# ---- images and numbers -----------------------------------------------------------------

def load_exr(path):
    image = bpy.data.images.load(path, check_existing=False)
    try:
        width, height = image.size
        pixels = np.empty(width * height * 4, dtype=np.float32)
        image.pixels.foreach_get(pixels)
    finally:
        bpy.data.images.remove(image)
    return pixels.reshape(height, width, 4)[::-1]  # rows top-down, for the figure


def difference_numbers(a, b):
    """Numbers of image a against image b (linear RGB): RMSE, mean |a − b|, Σa/Σb."""
    a, b = a[..., :3].astype(np.float64), b[..., :3].astype(np.float64)
    total_b = float(b.sum())
    return {"rmse": float(np.sqrt(np.mean((a - b) ** 2))),
            "mean_abs": float(np.mean(np.abs(a - b))),
            "energy_ratio": float(a.sum() / total_b) if total_b > 0 else float("nan")}


def display_scale(images):
    """One exposure for every image (so they stay comparable): the 99th percentile of all their
    linear values maps to white."""
    values = np.concatenate([i[..., :3].ravel() for i in images.values()])
    top = float(np.percentile(values, 99)) if values.size else 1.0
    return 1.0 / top if top > 0 else 1.0


def _display(image, scale=1.0):
    """Linear × scale → sRGB for showing (the EXRs stay linear)."""
    rgb = np.clip(image[..., :3] * scale, 0.0, 1.0)
    return np.where(rgb <= 0.0031308, 12.92 * rgb, 1.055 * np.power(rgb, 1 / 2.4) - 0.055)


def write_figure(path, images, numbers):
    """One PNG: every engine's image under its name, the heat map |BxDF Lab − Cycles| with its
    colour scale, and the numbers under it."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = list(images)
    heat = "BXDF_LAB" in images and "CYCLES" in images
    columns = len(names) + (1 if heat else 0)
    n_lines = len(numbers) + 1
    text_height = 0.17 * n_lines + 0.1  # inches under the images for the numbers
    figure, axes = plt.subplots(1, columns, figsize=(3.2 * columns, 2.6 + text_height), squeeze=False)
    scale = display_scale(images)
    for ax, name in zip(axes[0], names):
        ax.imshow(_display(images[name], scale))
        ax.set_title(ENGINE_NAMES.get(name, name))
        ax.axis("off")
    if heat:
        ax = axes[0][-1]
        diff = np.abs(images["BXDF_LAB"][..., :3] - images["CYCLES"][..., :3]).mean(axis=2)
        shown = ax.imshow(diff, cmap="inferno", vmin=0.0, vmax=max(float(np.percentile(diff, 99)), 1e-6))
        figure.colorbar(shown, ax=ax, fraction=0.046, pad=0.04, label="|BxDF Lab − Cycles|")
        ax.set_title("Difference")
        ax.axis("off")
    lines = [f"{ENGINE_NAMES[a]} vs {ENGINE_NAMES[b]}: RMSE {n['rmse']:.4g}, "
             f"mean |diff| {n['mean_abs']:.4g}, energy ratio {n['energy_ratio']:.4f}"
             for (a, b), n in numbers.items()]
    lines.append(f"Shown as linear radiance × {scale:.3g} (one exposure for all), sRGB; "
                 "the difference in linear radiance")
    figure.text(0.5, 0.02, "\n".join(lines), ha="center", va="bottom", fontsize=9)
    figure.tight_layout(rect=(0, text_height / (2.6 + text_height), 1, 1))
    figure.savefig(path, dpi=100)
    plt.close(figure)


def write_report(path, results, numbers, pairing_rows, options, figure_name):
    """A static HTML page: the figure, each engine's status and time, the numbers, and each
    material's pairing label and why."""
    esc = html.escape
    rows = "".join(
        f"<tr><td>{esc(ENGINE_NAMES[r.engine])}</td><td>{'rendered' if r.ok else 'failed'}</td>"
        f"<td>{r.seconds:.2f} s</td><td>{esc(os.path.basename(r.path) if r.ok else r.message)}</td></tr>"
        for r in results)
    number_rows = "".join(
        f"<tr><td>{esc(ENGINE_NAMES[a])} vs {esc(ENGINE_NAMES[b])}</td><td>{n['rmse']:.4g}</td>"
        f"<td>{n['mean_abs']:.4g}</td><td>{n['energy_ratio']:.4f}</td></tr>"
        for (a, b), n in numbers.items())
    pairing_html = "".join(
        f"<tr><td>{esc(p['material'])}</td><td>{esc(p['model'])}</td>"
        + "".join(f"<td class='{esc(p[e][0])}'><b>{esc(p[e][0])}</b>: {esc(p[e][1])}</td>"
                  for e in ("CYCLES", "POVRAY_RENDER")) + "</tr>"
        for p in pairing_rows)
    coverage_html = "".join(
        f"<tr><td>{esc(p['material'])}</td><td>{esc(n['node'])}</td><td>{esc(n['type'])}</td>"
        f"<td class='{esc(n['status'])}'>{esc(n['status'])}</td><td>{esc(n['why'])}</td></tr>"
        for p in pairing_rows for n in p["coverage"]) or (
        "<tr><td colspan=5>no material uses a node tree: every material is the panel's model</td></tr>")
    page = f"""<!DOCTYPE html><html><head><meta charset="utf-8"><title>BxDF Lab comparison</title>
<style>body{{font-family:sans-serif;margin:2em;max-width:70em}} td,th{{border:1px solid #ccc;
padding:.3em .6em;vertical-align:top}} table{{border-collapse:collapse;margin:1em 0}}
img{{max-width:100%}} .exact{{background:#e3f6e3}} .approximate{{background:#fff4d6}} .unsupported{{background:#fbe0e0}}</style>
</head><body><h1>BxDF Lab, Cycles and POV-Ray</h1>
<p>{esc(bpy.data.filepath or "unsaved scene")}, {time.strftime("%Y-%m-%d %H:%M")}: longest side
{options.size} px, {options.samples} samples per pixel (BxDF Lab and Cycles). Linear EXRs are in
this folder.</p>
<img src="{esc(figure_name)}" alt="renders side by side with the difference">
<h2>Renders</h2><table><tr><th>engine</th><th>status</th><th>time</th><th>image or error</th></tr>{rows}</table>
<h2>Differences</h2><table><tr><th>pair</th><th>RMSE</th><th>mean |diff|</th><th>energy ratio Σa/Σb</th></tr>
{number_rows}</table>
<h2>Materials</h2><p>How each material is paired: <b>exact</b> (same formula: the difference is
noise), <b>approximate</b> (best mapping: the difference is the finding) or <b>unsupported</b>.</p>
<table><tr><th>material</th><th>BxDF Lab model</th><th>Cycles</th><th>POV-Ray</th></tr>{pairing_html}</table>
<h2>Node coverage</h2><p>Each node of each material's tree: translated exactly, approximately,
or not at all.</p>
<table><tr><th>material</th><th>node</th><th>type</th><th>status</th><th>why</th></tr>{coverage_html}</table>
</body></html>"""
    with open(path, "w", encoding="utf-8") as f:
        f.write(page)


# ---- the run ------------------------------------------------------------------------------

@dataclass
class CompareRun:
    scene: object
    options: Options
    results: list = field(default_factory=list)
    addons: AddonsForRun = field(default_factory=AddonsForRun)
    _saved: list = field(default_factory=list)
    _started: float = 0.0

    def __post_init__(self):
        self.options.folder = bpy.path.abspath(self.options.folder)
        os.makedirs(self.options.folder, exist_ok=True)
        self.pending = list(ENGINES)
        # Every add-on the run needs is enabled now, before any render job: registering an
        # add-on's classes and properties while a job's thread reads the scene is not safe.
        self.enabled = {engine_id for engine_id in ENGINES if self.addons.need(engine_id)}

    def path(self, engine_id):
        return os.path.join(self.options.folder, f"{engine_id.lower()}.exr")

    def begin(self, engine_id):
        """Prepares `engine_id`'s render (settings, add-on, file path); False if it cannot run
        (recorded in results)."""
        result = EngineResult(engine_id, path=self.path(engine_id))
        self.results.append(result)
        if engine_id not in self.enabled or engine_id not in available_engines():
            result.message = f"{ENGINE_NAMES[engine_id]} is not available (its add-on did not enable)"
            return False
        if os.path.exists(result.path):
            os.remove(result.path)
        self._saved = apply_settings(engine_settings(self.scene, engine_id, self.options))
        self.scene.render.filepath = result.path
        self._started = time.perf_counter()
        return True

    def end(self, error=""):
        """Restores the settings after the current engine's render and records its outcome."""
        result = self.results[-1]
        result.seconds = time.perf_counter() - self._started
        restore_settings(self._saved)
        self._saved = []
        if not error and result.engine == "BXDF_LAB" and engine.last_error:
            error = engine.last_error
        if not error and not os.path.exists(result.path):
            error = f"{ENGINE_NAMES[result.engine]} wrote no image"
        result.ok, result.message = not error, error or result.path

    def render_blocking(self, engine_id):
        if not self.begin(engine_id):
            return
        try:
            bpy.ops.render.render(write_still=True, scene=self.scene.name)
            error = ""
        except RuntimeError as exc:  # an engine's error report
            error = str(exc)
        self.end(error)

    def abort(self):
        """Stops the run: restores whatever the current step changed and the add-ons."""
        if self._saved:
            restore_settings(self._saved)
            self._saved = []
        self.addons.restore()

    def finish(self):
        """Images, numbers, figure and report; the Blender image holding the figure."""
        self.addons.restore()
        images = {r.engine: load_exr(r.path) for r in self.results if r.ok}
        numbers = {}
        for a, b in (("BXDF_LAB", "CYCLES"), ("BXDF_LAB", "POVRAY_RENDER"), ("CYCLES", "POVRAY_RENDER")):
            if a in images and b in images and images[a].shape == images[b].shape:
                numbers[(a, b)] = difference_numbers(images[a], images[b])
        folder = self.options.folder
        figure_path = os.path.join(folder, "comparison.png")
        report_path = os.path.join(folder, "index.html")
        pairing_rows = pairings(self.scene)
        image = None
        if images:
            write_figure(figure_path, images, numbers)
            image = bpy.data.images.get(RESULT_IMAGE)
            if image is not None:
                bpy.data.images.remove(image)
            image = bpy.data.images.load(figure_path, check_existing=False)
            image.name = RESULT_IMAGE
        write_report(report_path, self.results, numbers, pairing_rows, self.options,
                     os.path.basename(figure_path))
        last_result.clear()
        last_result.update(folder=folder, report=report_path, figure=figure_path if images else "",
                           numbers=numbers, pairings=pairing_rows,
                           results=[(r.engine, r.ok, r.message) for r in self.results])
        return image
