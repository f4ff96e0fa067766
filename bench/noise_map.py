"""Where one engine's error exceeds the other's: per-pixel squared error of BXDF_LAB and Cycles.

Renders a harness scene with both engines (set up as bench/side_by_side.py sets them up, 2
threads), `--renders` seeds each at `--spp`, against the mean of both engines' `--reference-spp`
renders, and prints each engine's MSE, how much of BXDF_LAB's excess squared error the worst
100 pixels hold, and those pixels with each engine's largest single-render error (a firefly
shows as one render far off where the other engine never is). `--save DIR` writes .npy files:
the mean reference, and per engine its own reference, its renders (renders x H x W x 3) and
their squared error (renders x H x W).

    blender -b --factory-startup --python-exit-code 1 --python bench/noise_map.py -- \\
        --scene sweep_principled_transmission --spp 64 --renders 12
"""
import argparse
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import side_by_side  # noqa: E402


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="noise_map.py", description=__doc__.splitlines()[0])
    p.add_argument("--scene", default="cornell", help="harness scene name (compare/scenes.py)")
    p.add_argument("--spp", type=int, default=64, help="samples per render")
    p.add_argument("--renders", type=int, default=12, help="renders (seeds) per engine")
    p.add_argument("--first-seed", type=int, default=0,
                   help="seeds first-seed .. first-seed + renders - 1 (another set of renders)")
    p.add_argument("--reference-spp", type=int, default=1024, help="samples of each reference")
    p.add_argument("--threads", type=int, default=2, help="threads for both engines")
    p.add_argument("--worst", type=int, default=10, help="pixels to list")
    p.add_argument("--save", default=None, help="folder for the .npy maps")
    args = p.parse_args(argv)
    if args.first_seed < 0:
        p.error(f"--first-seed must be at least 0, got {args.first_seed}")
    for name in ("spp", "renders", "reference_spp", "threads", "worst"):
        if getattr(args, name) < 1:
            p.error(f"--{name.replace('_', '-')} must be at least 1, got {getattr(args, name)}")
    return args


def main():
    args = parse_args()
    side_by_side.use_module_paths()
    import numpy as np

    spec, _ = side_by_side.set_up_scene(args.scene, None)
    work = tempfile.mkdtemp(prefix="bxdf-noise-map-")
    engines = side_by_side.ENGINES
    refs, reference = side_by_side.render_references(spec, args.reference_spp, args.threads, work)
    images = {e: [] for e in engines}
    for seed in range(args.first_seed, args.first_seed + args.renders):
        for e in engines:
            images[e].append(side_by_side.render(e, spec, args.spp, seed, args.threads,
                                                 os.path.join(work, f"{e}_{seed}.exr"))[2])
    images = {e: np.stack(images[e]) for e in engines}
    maps = {e: ((images[e] - reference) ** 2).mean(axis=3) for e in engines}
    mse = {e: float(maps[e].mean()) for e in engines}
    print(f"noise_map: {args.scene}, {args.renders} renders per engine at {args.spp} spp "
          f"(seeds {args.first_seed}-{args.first_seed + args.renders - 1}), "
          f"{args.threads} threads, reference = mean of both at {args.reference_spp} spp")
    print("  MSE " + ", ".join(f"{e} {mse[e]:.4g}" for e in engines) +
          f"; ratio {mse[engines[0]] / mse[engines[1]]:.3f}; MSE between the references "
          f"{float(((refs[0] - refs[1]) ** 2).mean()):.3g}")
    excess = maps[engines[0]].mean(axis=0) - maps[engines[1]].mean(axis=0)
    order = np.argsort(excess.ravel())[::-1]
    total = float(excess.sum())
    if total > 0:
        print(f"  the worst 100 pixels hold {float(excess.ravel()[order[:100]].sum()) / total:.0%} "
              f"of {engines[0]}'s excess squared error ({total:.4g} summed)")
    width = excess.shape[1]
    print(f"  {'row':>5} {'col':>5} " +
          " ".join(f"{e + ' mean':>14} {e + ' max':>14}" for e in engines))
    for k in order[:args.worst]:
        y, x = divmod(int(k), width)
        print(f"  {y:>5} {x:>5} " + " ".join(
            f"{float(maps[e][:, y, x].mean()):>14.4g} {float(maps[e][:, y, x].max()):>14.4g}"
            for e in engines))
    if args.save:
        os.makedirs(args.save, exist_ok=True)
        np.save(os.path.join(args.save, f"{args.scene}_reference.npy"), reference)
        for e, own_reference in zip(engines, refs):
            np.save(os.path.join(args.save, f"{args.scene}_{e}_reference.npy"), own_reference)
            np.save(os.path.join(args.save, f"{args.scene}_{e}_renders.npy"), images[e])
            np.save(os.path.join(args.save, f"{args.scene}_{e}_squared_error.npy"), maps[e])


if __name__ == "__main__":
    main()
