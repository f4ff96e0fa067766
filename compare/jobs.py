"""One job = one scene in one engine. Blender engines run as `blender -b` subprocesses (driver.py);
ANALYTIC runs in the worker process. Jobs are plain dicts and the functions are module-level, so
the same job runs in a local process pool or on a Dask worker (which must see the same file system
and have this repository on its Python path)."""
from __future__ import annotations

import json
import os
import subprocess
import sys
import time
import traceback

STOCHASTIC = ("CYCLES", "BXDF_LAB")
# Independent renders per stochastic engine, spp/4 samples each; their spread is the noise
# estimate. Four, not two halves: with stratified sampling two halves often agree while both are off
# (metrics.py, issue #12).
SEEDS = (1, 2, 3, 4)


def make_job(scene, engine, spp, resolution, run_dir, repo_root, blender, threads, timeout,
             python_paths=(), overrides=None):
    out_dir = os.path.join(run_dir, "renders", scene)
    return {"scene": scene, "engine": engine, "spp": max(1, spp // len(SEEDS)),
            "seeds": list(SEEDS), "resolution": list(resolution) if resolution else None,
            "out_dir": out_dir, "repo_root": repo_root, "blender": blender, "threads": threads,
            "timeout": timeout, "python_paths": list(python_paths), "overrides": overrides or {}}


def run_job(job: dict) -> dict:
    """Never raises: a failure is a result with status 'failed' and the log that says why."""
    os.makedirs(job["out_dir"], exist_ok=True)
    log_path = os.path.join(job["out_dir"], f"{job['engine']}.log")
    start = time.perf_counter()
    try:
        if job["engine"] == "ANALYTIC":
            status, message = _run_analytic(job, log_path)
        else:
            status, message = _run_blender(job, log_path)
    except Exception:  # noqa: BLE001 - recorded, never lost
        status, message = "failed", traceback.format_exc()
        with open(log_path, "a", encoding="utf-8") as fh:
            fh.write(message)
    return {"scene": job["scene"], "engine": job["engine"], "status": status,
            "message": message, "wall_seconds": time.perf_counter() - start,
            "log": os.path.relpath(log_path, os.path.dirname(os.path.dirname(job["out_dir"])))}


def _run_blender(job, log_path):
    job_path = os.path.join(job["out_dir"], f"{job['engine']}.job.json")
    with open(job_path, "w", encoding="utf-8") as fh:
        json.dump(job, fh, indent=1)
    meta_path = os.path.join(job["out_dir"], f"{job['engine']}.meta.json")
    if os.path.exists(meta_path):
        os.remove(meta_path)
    driver = os.path.join(job["repo_root"], "compare", "driver.py")
    cmd = [job["blender"], "-b", "--factory-startup", "--python-exit-code", "1",
           "--python", driver, "--", job_path]
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([job["repo_root"]] + job["python_paths"]
                                        + [p for p in [env.get("PYTHONPATH")] if p])
    with open(log_path, "w", encoding="utf-8") as log:
        log.write("$ " + " ".join(cmd) + "\n")
        log.flush()
        try:
            proc = subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT, env=env,
                                  timeout=job["timeout"], check=False)
        except subprocess.TimeoutExpired:
            log.write(f"\n[compare] timed out after {job['timeout']} s\n")
            return "failed", f"timed out after {job['timeout']} s"
    if proc.returncode != 0:
        return "failed", f"blender exited with code {proc.returncode}: {_tail(log_path)}"
    if not os.path.isfile(meta_path):
        return "failed", f"blender exited 0 but wrote no {os.path.basename(meta_path)}"
    return "ok", ""


def _run_analytic(job, log_path):
    import numpy as np

    from . import analytic, imageio, scenes
    from dataclasses import replace

    for path in job["python_paths"]:
        if path not in sys.path:
            sys.path.insert(0, path)
    spec = scenes.get(job["scene"])
    if job["resolution"]:
        spec = replace(spec, resolution=tuple(job["resolution"]))
    start = time.perf_counter()
    result = analytic.render(spec)
    seconds = time.perf_counter() - start
    imageio.write_exr(os.path.join(job["out_dir"], "ANALYTIC.exr"), result.image)
    imageio.write_exr(os.path.join(job["out_dir"], "ANALYTIC.tolerance.exr"),
                      result.geometry_tolerance)
    np.save(os.path.join(job["out_dir"], "ANALYTIC.ids.npy"), result.object_ids)
    import bxdf  # noqa: PLC0415 - analytic.render has imported it from python_paths

    source = f"bxdf.make(...).f (core) from {os.path.dirname(bxdf.__file__)}"
    meta = {"scene": job["scene"], "engine": "ANALYTIC", "f_from": source,
            "renders": [{"seed": None, "seconds": seconds, "image": "ANALYTIC.exr"}]}
    with open(os.path.join(job["out_dir"], "ANALYTIC.meta.json"), "w", encoding="utf-8") as fh:
        json.dump(meta, fh, indent=1)
    with open(log_path, "w", encoding="utf-8") as fh:
        fh.write(f"analytic image in {seconds:.3f} s, f from {source}\n")
    return "ok", ""


def _tail(path, lines=6):
    with open(path, encoding="utf-8", errors="replace") as fh:
        return " | ".join(line.strip() for line in fh.readlines()[-lines:] if line.strip())
