"""The harness runs its jobs on a Dask cluster given --scheduler (here a local one on loopback)."""
import os

from harness_helpers import REPO, run_compare


def test_run_through_a_dask_scheduler_on_loopback(tmp_path, monkeypatch):
    from distributed import LocalCluster

    # Workers unpickle compare.jobs.run_job: they need the repository on their path.
    monkeypatch.setenv("PYTHONPATH", REPO + os.pathsep + os.environ.get("PYTHONPATH", ""))
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=True, host="127.0.0.1",
                      dashboard_address=None) as cluster:
        assert cluster.scheduler_address.startswith("tcp://127.0.0.1:")
        run_dir, summary = run_compare(tmp_path, "--scenes", "lit_lambertian",
                                       "--engines", "CYCLES", "--res", "16", "16", "--spp", "4",
                                       "--scheduler", cluster.scheduler_address)
    assert summary["settings"]["scheduler"] == cluster.scheduler_address
    engines = summary["scenes"][0]["engines"]
    assert engines["CYCLES"]["status"] == "ok", engines["CYCLES"]
    assert engines["ANALYTIC"]["status"] == "ok"
    p = summary["scenes"][0]["pairings"][0]
    assert (p["a"], p["b"], p["label"], p["pass"]) == ("CYCLES", "ANALYTIC", "exact", True)
