"""Runs every (scene, engine) job in a local process pool or on a Dask cluster, with a progress
bar, into a fresh run folder out/<run-id>/, then writes the report there."""
from __future__ import annotations

import concurrent.futures
import datetime
import os
import sys
import time

from . import jobs, report, scenes

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def new_run_dir(out_root: str) -> str:
    """out_root/<UTC timestamp>[-k]: created here, never reused, so no run overwrites another."""
    stamp = datetime.datetime.now(datetime.timezone.utc).strftime("%Y%m%d-%H%M%S")
    os.makedirs(out_root, exist_ok=True)
    for k in range(1000):
        path = os.path.join(out_root, stamp if k == 0 else f"{stamp}-{k}")
        try:
            os.makedirs(path)
        except FileExistsError:
            continue
        return path
    raise RuntimeError(f"cannot create a new run folder under {out_root}")


def bxdf_python_paths() -> list:
    """Where the compiled `bxdf` module may live: $BXDF_PYTHONPATH, then the usual build folders."""
    paths = [p for p in os.environ.get("BXDF_PYTHONPATH", "").split(os.pathsep) if p]
    for build in ("build", "build-release"):
        candidate = os.path.join(REPO_ROOT, build, "python")
        if os.path.isdir(candidate):
            paths.append(candidate)
    return paths


class ProgressBar:
    def __init__(self, total, stream=sys.stderr, width=30):
        self.total, self.done, self.failed = total, 0, 0
        self.stream, self.width = stream, width
        self.start = time.perf_counter()
        self.tty = hasattr(stream, "isatty") and stream.isatty()
        self._draw("")

    def advance(self, result):
        self.done += 1
        self.failed += result["status"] != "ok"
        label = f"{result['scene']} {result['engine']} {result['status']}"
        self._draw(label)

    def _draw(self, label):
        filled = int(self.width * self.done / max(self.total, 1))
        bar = "#" * filled + "." * (self.width - filled)
        elapsed = time.perf_counter() - self.start
        text = (f"[{bar}] {self.done}/{self.total} jobs, {self.failed} failed, "
                f"{elapsed:5.0f} s  {label}")
        if self.tty:
            self.stream.write("\r" + text[:150].ljust(150))
            if self.done == self.total:
                self.stream.write("\n")
        elif label:
            self.stream.write(text + "\n")
        self.stream.flush()


def _expected_cost(job, spec):
    w, h = job["resolution"] or spec.resolution
    return w * h * (spec.spp if spec.max_bounces == 0 else spec.spp * (1 + spec.max_bounces))


def run(scene_names, engines, spp=None, resolution=None, out_root="out", scheduler=None,
        workers=2, blender="blender", timeout=900, overrides=None, quiet=False) -> str:
    specs = [scenes.get(name) for name in scene_names]
    run_dir = new_run_dir(out_root)
    python_paths = bxdf_python_paths()
    for path in python_paths:   # the report's plots use `bxdf` in this process too
        if path not in sys.path:
            sys.path.append(path)
    threads = max(1, (os.cpu_count() or 2) // max(workers, 1)) if scheduler is None else 0
    job_list = []
    for spec in specs:
        wanted = list(engines)
        if spec.has_analytic_truth() and "ANALYTIC" not in wanted:
            wanted.append("ANALYTIC")
        if not spec.has_analytic_truth() and "ANALYTIC" in wanted:
            wanted.remove("ANALYTIC")
        for engine in wanted:
            job_list.append(jobs.make_job(
                spec.name, engine, spp or spec.spp, resolution, run_dir, REPO_ROOT, blender,
                threads, timeout, python_paths, overrides))
    by_name = {s.name: s for s in specs}
    job_list.sort(key=lambda j: -_expected_cost(j, by_name[j["scene"]]))

    settings = {"scenes": scene_names, "engines": list(engines), "spp": spp,
                "resolution": list(resolution) if resolution else None,
                "scheduler": scheduler, "workers": workers, "threads_per_job": threads,
                "python_paths": python_paths, "overrides": overrides or {}}
    started = time.perf_counter()
    results = _execute(job_list, scheduler, workers, quiet)
    settings["wall_seconds"] = time.perf_counter() - started
    report.write(run_dir, specs, job_list, results, settings)
    return run_dir


def _execute(job_list, scheduler, workers, quiet):
    progress = ProgressBar(len(job_list), stream=open(os.devnull, "w") if quiet else sys.stderr)
    results = []
    if scheduler:
        from distributed import Client, as_completed  # noqa: PLC0415 - only with --scheduler

        with Client(scheduler, timeout="30s") as client:
            job_by_key, futures = {}, []
            for job in job_list:
                key = f"compare-{job['scene']}-{job['engine']}-{time.time_ns()}"
                job_by_key[key] = job
                futures.append(client.submit(jobs.run_job, job, pure=False, key=key))
            for future in as_completed(futures):
                result = _result_or_failure(future.result, job_by_key[future.key])
                results.append(result)
                progress.advance(result)
    else:
        with concurrent.futures.ProcessPoolExecutor(max_workers=workers) as pool:
            futures = {pool.submit(jobs.run_job, job): job for job in job_list}
            for future in concurrent.futures.as_completed(futures):
                result = _result_or_failure(future.result, futures[future])
                results.append(result)
                progress.advance(result)
    return results


def _result_or_failure(get, job):
    """A worker that died (not a job that failed: run_job never raises) still yields a result."""
    try:
        return get()
    except Exception as exc:  # noqa: BLE001
        return {"scene": job["scene"], "engine": job["engine"], "status": "failed",
                "message": f"worker failed: {type(exc).__name__}: {exc}", "wall_seconds": 0.0,
                "log": None}
