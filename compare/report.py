"""Turns the renders of one run into out/<run>/summary.json and out/<run>/index.html (a static page
with relative links only): images side by side, heat maps, the table of figures per pairing,
render times against Cycles (BXDF_LAB/CYCLES per scene), and lobe / albedo plots per material."""
from __future__ import annotations

import html
import json
import math
import os

import numpy as np

from . import imageio, metrics, pairings, plots
from .jobs import STOCHASTIC
from .scene_spec import NODES

ENGINE_ORDER = ("ANALYTIC", "CYCLES", "BXDF_LAB", "POVRAY_RENDER")
POV_SATURATION = 65534.5 / 65535.0


def to_display(image):
    """Linear -> sRGB 8-bit for the page (exposure 1, clipped: the Standard view transform)."""
    x = np.clip(image, 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)


def _json_safe(value):
    if isinstance(value, dict):
        return {k: _json_safe(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_json_safe(v) for v in value]
    if isinstance(value, (np.floating, float)):
        return float(value) if math.isfinite(value) else None
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.bool_):
        return bool(value)
    return value


def _load_meta(render_dir, engine):
    path = os.path.join(render_dir, f"{engine}.meta.json")
    with open(path, encoding="utf-8") as fh:
        return json.load(fh)


def _load_engine(run_dir, spec, engine, result):
    """(entry for summary.json, image, variance or None, truth or None), where truth holds the
    analytic image's object ids and geometric tolerance."""
    render_dir = os.path.join(run_dir, "renders", spec.name)
    entry = {"status": result["status"], "seconds": None, "wall_seconds": result["wall_seconds"],
             "image": None, "log": result.get("log"), "message": result.get("message", "")}
    if result["status"] != "ok":
        return entry, None, None, None
    try:
        meta = _load_meta(render_dir, engine)
        entry["seconds"] = float(sum(r["seconds"] for r in meta["renders"]))
        entry["settings"] = meta.get("settings", {})
        entry["materials"] = meta.get("materials", {})
        if "f_from" in meta:
            entry["f_from"] = meta["f_from"]
        variance, truth = None, None
        if engine in STOCHASTIC:
            renders = [imageio.read(os.path.join(render_dir, r["image"])) for r in meta["renders"]]
            image = sum(renders) / len(renders)
            variance = metrics.variance_of_mean(*renders)
            path = os.path.join(render_dir, f"{engine}.exr")
            imageio.write_exr(path, image)
        else:
            path = os.path.join(render_dir, meta["renders"][0]["image"])
            image = imageio.read(path)
            if engine == "ANALYTIC":
                truth = {"ids": np.load(os.path.join(render_dir, "ANALYTIC.ids.npy")),
                         "geometry": imageio.read(os.path.join(render_dir,
                                                               "ANALYTIC.tolerance.exr"))}
        entry["image"] = os.path.relpath(path, run_dir)
        return entry, image, variance, truth
    except Exception as exc:  # noqa: BLE001 - a broken output is a failed engine, not a lost run
        entry["status"] = "failed"
        entry["message"] = f"output unreadable: {type(exc).__name__}: {exc}"
        return entry, None, None, None


def analyse(run_dir, spec, results):
    scene_dir = os.path.join(run_dir, "report", spec.name)
    os.makedirs(scene_dir, exist_ok=True)
    engines, images, variances, truth = {}, {}, {}, None
    for engine in ENGINE_ORDER:
        if engine not in results:
            continue
        entry, image, variance, analytic_truth = _load_engine(run_dir, spec, engine,
                                                              results[engine])
        if image is not None:
            images[engine], variances[engine] = image, variance
            display = os.path.join(scene_dir, f"{engine}.png")
            imageio.write_png8(display, to_display(image))
            entry["display"] = os.path.relpath(display, run_dir)
        if analytic_truth is not None:
            truth = analytic_truth
        engines[engine] = entry

    # Render seconds (all seeds, the same samples and threads) over Cycles': below 1 is faster.
    cycles_seconds = engines.get("CYCLES", {}).get("seconds")
    for entry in engines.values():
        if cycles_seconds and entry.get("seconds"):
            entry["time_vs_cycles"] = entry["seconds"] / cycles_seconds

    shapes = {img.shape for img in images.values()}
    mask = ~metrics.edge_mask(truth["ids"]) if truth is not None else None
    geometry = truth["geometry"] if truth is not None else None
    pair_list = []
    size_error = f"image sizes differ: {sorted(shapes)}" if len(shapes) > 1 else ""
    for a, b in pairings.pairs(list(images)):
        label = pairings.label(spec, a, b)
        item = {"a": a, "b": b, "label": label}
        if size_error:
            item.update({"rmse": None, "z_fail_fraction": None, "pass": False, "flagged": True,
                         "error": size_error})
            pair_list.append(item)
            continue
        pair_mask = np.ones(images[a].shape[:2], bool) if mask is None else mask.copy()
        # POV-Ray's 16-bit PNG clips at 1: a clipped pixel says nothing about the shading.
        saturated = np.zeros_like(pair_mask)
        for engine in (a, b):
            if engine == "POVRAY_RENDER":
                saturated |= images[engine].max(axis=-1) >= POV_SATURATION
        pair_mask &= ~saturated
        figures = metrics.compare(images[a], images[b], variances[a], variances[b], pair_mask,
                                  systematic=geometry if "ANALYTIC" in (a, b) else None)
        ok = metrics.passes(figures)
        heat = os.path.join(scene_dir, f"diff_{a}_vs_{b}.png")
        plots.heatmap(figures["diff_image"], figures["z_image"], figures["fail_image"],
                      metrics.Z_CRIT, f"{spec.name}: {a} vs {b} ({label})", heat)
        item.update({k: v for k, v in figures.items() if not k.endswith("_image")})
        item.update({"pass": ok, "flagged": label == "exact" and not ok,
                     "heatmap": os.path.relpath(heat, run_dir),
                     "edge_pixels_excluded": int((~mask).sum()) if mask is not None else 0,
                     "saturated_pixels_excluded": int(saturated.sum())})
        # The add-on's own label for each material's mapping (set-up operators); an exact pairing
        # whose mapping the add-on calls approximate is a contradiction the page shows.
        addon_labels = {e: {m: v.get("addon_label")
                            for m, v in engines[e].get("materials", {}).items()}
                        for e in (a, b) if engines[e].get("materials")}
        item["addon_labels"] = addon_labels
        if label == "exact" and any(v != "exact" for labels in addon_labels.values()
                                    for v in labels.values()):
            item["error"] = f"the add-on labels a mapping of this exact pairing: {addon_labels}"
        if label == "approximate":
            item["approximations"] = pairings.approximations(spec, a, b)
            item["mapping"] = {e: {m: v.get("renders_as", "")
                                   for m, v in engines[e].get("materials", {}).items()}
                               for e in (a, b) if engines[e].get("materials")}
        pair_list.append(item)
    return {"name": spec.name, "description": spec.description,
            "resolution": list(images[next(iter(images))].shape[1::-1]) if images else None,
            "materials": [{"name": m.name, "model": m.model, "params": m.params}
                          for m in spec.materials()],
            "engines": engines, "pairings": pair_list}


def material_plots(run_dir, specs):
    out = {}
    plot_dir = os.path.join(run_dir, "report", "materials")
    os.makedirs(plot_dir, exist_ok=True)
    for spec in specs:
        for material in spec.materials():
            if material.name in out:
                continue
            entry = {"model": material.model, "params": material.params}
            if material.model == NODES:
                entry["plot_error"] = "a Blender node material: no single model to plot"
                out[material.name] = entry
                continue
            try:
                lobe = os.path.join(plot_dir, f"{material.name}_lobe.png")
                albedo = os.path.join(plot_dir, f"{material.name}_albedo.png")
                plots.lobe_plot(material, lobe)
                theta_o, rho = plots.albedo_plot(material, albedo)
                entry.update({"lobe_plot": os.path.relpath(lobe, run_dir),
                              "albedo_plot": os.path.relpath(albedo, run_dir),
                              "albedo_curve": {"theta_o_deg": np.degrees(theta_o).tolist(),
                                               "rho": rho.tolist()}})
            except (NotImplementedError, ValueError) as exc:
                entry["plot_error"] = str(exc)
            out[material.name] = entry
    return out


def write(run_dir, specs, job_list, results, settings):
    by_scene = {}
    for result in results:
        by_scene.setdefault(result["scene"], {})[result["engine"]] = result
    summary = {"run": os.path.basename(run_dir), "settings": settings,
               "thresholds": {"z_crit": metrics.Z_CRIT, "rel_tol": metrics.REL_TOL,
                              "abs_tol": metrics.ABS_TOL, "pass_fraction": metrics.PASS_FRACTION,
                              "signal_level": metrics.SIGNAL_LEVEL},
               "scenes": [analyse(run_dir, spec, by_scene.get(spec.name, {})) for spec in specs],
               "materials": material_plots(run_dir, specs)}
    summary = _json_safe(summary)
    with open(os.path.join(run_dir, "summary.json"), "w", encoding="utf-8") as fh:
        json.dump(summary, fh, indent=1, allow_nan=False)
    with open(os.path.join(run_dir, "index.html"), "w", encoding="utf-8") as fh:
        fh.write(render_html(summary))
    return summary


# ---- HTML -------------------------------------------------------------------------------------

CSS = """
body { font-family: sans-serif; margin: 1.5em; color: #222; }
table { border-collapse: collapse; margin: 0.5em 0 1em; font-size: 0.85em; }
td, th { border: 1px solid #bbb; padding: 2px 6px; text-align: right; }
th { background: #eee; } td.l, th.l { text-align: left; }
tr.flagged td { background: #f8c0c0; } tr.passed td.verdict { background: #c8ecc8; }
.status-failed { color: #b00; font-weight: bold; }
figure { display: inline-block; margin: 0 8px 8px 0; text-align: center; font-size: 0.8em; }
figure img.render { image-rendering: pixelated; width: 256px; }
.note { font-size: 0.8em; color: #555; }
pre { font-size: 0.75em; background: #f4f4f4; padding: 4px; white-space: pre-wrap; }
"""


def _e(text):
    return html.escape(str(text), quote=True)


def _num(value, fmt="{:.4g}"):
    return "–" if value is None else fmt.format(value)


def render_html(summary):
    parts = ["<!DOCTYPE html>", "<html lang=\"en\"><head><meta charset=\"utf-8\">",
             f"<title>BxDF Lab comparison {_e(summary['run'])}</title>",
             f"<style>{CSS}</style></head><body>",
             f"<h1>BxDF Lab comparison — run {_e(summary['run'])}</h1>",
             "<p class=\"note\">Pairings are <b>exact</b> (same formula in both renderers: the "
             "difference must be Monte Carlo noise; a failing exact pairing is flagged red) or "
             "<b>approximate</b> (closest mapping: the difference is the finding). z-test: pixel "
             f"fails when |a−b| &gt; {summary['thresholds']['z_crit']:g} σ in a channel, σ² = "
             "noise variance of both images (from four quarter-sample renders with different "
             "seeds) + "
             "(against ANALYTIC) the closed form's change under the tessellated spheres' normal "
             f"error² + ({summary['thresholds']['rel_tol']:g}·value + "
             f"{summary['thresholds']['abs_tol']:g})²"
             "; an exact pairing passes when at most "
             f"{100 * summary['thresholds']['pass_fraction']:g}% of the signal pixels (either "
             f"image above {summary['thresholds']['signal_level']:g}) fail. Silhouette "
             "pixels are excluded where an analytic image exists, and pixels that POV-Ray's "
             "16-bit PNG clips at 1. Data: "
             "<a href=\"summary.json\">summary.json</a>.</p>",
             _run_settings(summary["settings"]),
             _render_times(summary), _overview(summary)]
    for scene in summary["scenes"]:
        parts.append(_scene_html(scene, summary["materials"]))
    parts.append("</body></html>")
    return "\n".join(parts)


def _run_settings(settings):
    wall = settings.get("wall_seconds")
    where = settings["scheduler"] or f"local pool of {settings['workers']} workers"
    resolution = settings["resolution"]
    resolution = "×".join(map(str, resolution)) if resolution else "per scene"
    return (f"<p class=\"note\">Wall time {_num(wall, '{:.0f}')} s on {_e(where)}, "
            f"{_e(settings['threads_per_job'] or 'all')} thread(s) per render; spp "
            f"{_e(settings['spp'] or 'per scene')}, resolution {_e(resolution)}. "
            "Time / Cycles = the engine's render seconds (all four quarter-sample renders, through "
            "Blender's render operator, scene export included) / Cycles' (below 1: faster).</p>"
            + _overrides_html(settings.get("overrides") or {}))


def _overrides_html(overrides):
    """A run with --override renders some materials wrongly on purpose: the page says which."""
    if not overrides:
        return ""
    items = "".join(f"<li>{_e(engine)}: material {_e(material)}: "
                    + ", ".join(f"{_e(k)} = {_e(v)}" for k, v in params.items()) + "</li>"
                    for engine, materials in overrides.items()
                    for material, params in materials.items())
    return ("<p class=\"note\"><b>This run used --override</b>: these parameters were changed in "
            "one engine only (a sensitivity check; an exact pairing involving them should fail):"
            f"</p><ul>{items}</ul>")


def _render_times(summary):
    """Per scene: Cycles' and BXDF_LAB's render seconds and their ratio (the speed finding)."""
    rows = ["<h2>Render time against Cycles</h2><table><tr><th class=\"l\">scene</th>"
            "<th>samples</th><th>CYCLES s</th><th>BXDF_LAB s</th><th>BXDF_LAB / CYCLES</th></tr>"]
    for scene in summary["scenes"]:
        engines = scene["engines"]
        cycles, lab = engines.get("CYCLES", {}), engines.get("BXDF_LAB", {})
        if cycles.get("seconds") is None and lab.get("seconds") is None:
            continue
        samples = (lab.get("settings") or cycles.get("settings") or {}).get("samples_total")
        rows.append(f"<tr><td class=\"l\"><a href=\"#{_e(scene['name'])}\">{_e(scene['name'])}"
                    f"</a></td><td>{_num(samples, '{}')}</td>"
                    f"<td>{_num(cycles.get('seconds'), '{:.2f}')}</td>"
                    f"<td>{_num(lab.get('seconds'), '{:.2f}')}</td>"
                    f"<td>{_num(lab.get('time_vs_cycles'), '{:.2f}')}</td></tr>")
    rows.append("</table>")
    return "\n".join(rows)


def _overview(summary):
    rows = ["<h2>Overview</h2><table><tr><th class=\"l\">scene</th>"
            "<th class=\"l\">pairing</th><th class=\"l\">label</th><th>RMSE</th><th>z fail</th>"
            "<th class=\"l\">verdict</th></tr>"]
    for scene in summary["scenes"]:
        for p in scene["pairings"]:
            rows.append(_pair_row_short(scene["name"], p))
    rows.append("</table>")
    return "\n".join(rows)


def _verdict(p):
    if p["label"] == "exact":
        return "pass" if p["pass"] else "FAIL"
    return "matches to noise" if p["pass"] else "differs (finding)"


def _pair_row_short(scene_name, p):
    cls = "flagged" if p.get("flagged") else ("passed" if p["pass"] else "")
    return (f"<tr class=\"{cls}\"><td class=\"l\"><a href=\"#{_e(scene_name)}\">{_e(scene_name)}"
            f"</a></td><td class=\"l\">{_e(p['a'])} vs {_e(p['b'])}</td><td class=\"l\">"
            f"{_e(p['label'])}</td><td>{_num(p.get('rmse'))}</td>"
            f"<td>{_num(p.get('z_fail_fraction'), '{:.2%}')}</td>"
            f"<td class=\"l verdict\">{_e(_verdict(p))}</td></tr>")


def _scene_html(scene, materials):
    out = [f"<h2 id=\"{_e(scene['name'])}\">{_e(scene['name'])}</h2>",
           f"<p>{_e(scene['description'])}</p>"]
    # Engines: status, times against Cycles.
    out.append("<table><tr><th class=\"l\">engine</th><th class=\"l\">status</th>"
               "<th>render s</th><th>wall s</th><th>time / Cycles</th>"
               "<th class=\"l\">settings</th><th class=\"l\">log</th></tr>")
    for engine, e in scene["engines"].items():
        status_cls = "status-failed" if e["status"] != "ok" else ""
        log = f"<a href=\"{_e(e['log'])}\">log</a>" if e.get("log") else ""
        settings = _e(json.dumps(e.get("settings", {}))) if e.get("settings") else ""
        if e.get("f_from"):
            settings = _e("f from " + e["f_from"])
        speed = _num(e.get("time_vs_cycles"), "{:.2f}")
        out.append(f"<tr><td class=\"l\">{_e(engine)}</td><td class=\"l {status_cls}\">"
                   f"{_e(e['status'])}</td><td>{_num(e.get('seconds'), '{:.2f}')}</td>"
                   f"<td>{_num(e.get('wall_seconds'), '{:.1f}')}</td><td>{speed}</td>"
                   f"<td class=\"l note\">{settings}</td><td class=\"l\">{log}</td></tr>")
        if e["status"] != "ok" and e.get("message"):
            out.append(f"<tr><td></td><td class=\"l\" colspan=\"6\"><pre>{_e(e['message'])}"
                       "</pre></td></tr>")
    out.append("</table>")
    # Images side by side.
    for engine, e in scene["engines"].items():
        if e.get("display"):
            out.append(f"<figure><img class=\"render\" src=\"{_e(e['display'])}\" "
                       f"alt=\"{_e(engine)} render of {_e(scene['name'])}\"><figcaption>"
                       f"{_e(engine)} (<a href=\"{_e(e['image'])}\">linear</a>)</figcaption>"
                       "</figure>")
    # Pairings.
    out.append("<table><tr><th class=\"l\">a vs b</th><th class=\"l\">label</th><th>mean</th>"
               "<th>RMSE</th><th>max</th><th>PSNR dB</th><th>rel MSE</th><th>Σa/Σb</th>"
               "<th>noise RMS</th><th>z fail</th><th class=\"l\">verdict</th></tr>")
    for p in scene["pairings"]:
        cls = "flagged" if p.get("flagged") else ("passed" if p["pass"] else "")
        out.append(f"<tr class=\"{cls}\"><td class=\"l\">{_e(p['a'])} vs {_e(p['b'])}</td>"
                   f"<td class=\"l\">{_e(p['label'])}</td><td>{_num(p.get('mean'))}</td>"
                   f"<td>{_num(p.get('rmse'))}</td><td>{_num(p.get('max_abs'))}</td>"
                   f"<td>{_num(p.get('psnr'), '{:.1f}')}</td><td>{_num(p.get('rel_mse'))}</td>"
                   f"<td>{_num(p.get('ratio_mean'), '{:.4f}')}</td>"
                   f"<td>{_num(p.get('noise_rms'))}</td>"
                   f"<td>{_num(p.get('z_fail_fraction'), '{:.2%}')}</td>"
                   f"<td class=\"l verdict\">{_e(_verdict(p))}</td></tr>")
        if p["label"] == "approximate" and (p.get("approximations") or p.get("mapping")):
            lines = list(p.get("approximations", []))
            for engine, mats in p.get("mapping", {}).items():
                for name, text in mats.items():
                    lines.append(f"{engine} renders {name} as: {text}")
            out.append("<tr><td></td><td class=\"l note\" colspan=\"10\">"
                       + "<br>".join(_e(x) for x in lines) + "</td></tr>")
        if p.get("error"):
            out.append(f"<tr><td></td><td class=\"l\" colspan=\"10\">{_e(p['error'])}</td></tr>")
    out.append("</table>")
    for p in scene["pairings"]:
        if p.get("heatmap"):
            out.append(f"<figure><img src=\"{_e(p['heatmap'])}\" alt=\"difference of "
                       f"{_e(p['a'])} and {_e(p['b'])}\"><figcaption>{_e(p['a'])} vs "
                       f"{_e(p['b'])}</figcaption></figure>")
    # Materials.
    out.append("<h3>Materials</h3>")
    for m in scene["materials"]:
        info = materials.get(m["name"], {})
        out.append(f"<p><b>{_e(m['name'])}</b>: {_e(m['model'])} "
                   f"{_e(json.dumps(m['params']))}</p>")
        for key in ("lobe_plot", "albedo_plot"):
            if info.get(key):
                out.append(f"<figure><img src=\"{_e(info[key])}\" alt=\"{_e(key)} of "
                           f"{_e(m['name'])}\"></figure>")
        if info.get("plot_error"):
            out.append(f"<p class=\"note\">plots: {_e(info['plot_error'])}</p>")
    return "\n".join(out)
