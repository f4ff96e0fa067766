"""Where BXDF_LAB's noise exceeds Cycles': the first spheres of principled_showroom, per pixel.

    blender -b --factory-startup --python-exit-code 1 --python bench/two_sphere_noise.py -- \
        --objects 2 --res 256 80 --spp 64 --seeds 6 --reference-spp 4096

Renders the scene's first `--objects` spheres (gold and the clear-coated plastic by default)
under its point light and grey world (`--lights light` or `world` keeps one), `--seeds` times per
engine at `--spp`, against the mean of both engines' `--reference-spp` renders, and prints each
engine's MSE, their ratio, and the ratio without the 1% of pixels where the engines' errors
differ most: when the two ratios disagree, the difference lives in a handful of pixels, and a
ratio taken from so few is no measure of an estimator (at 64x64 the two spheres are ~6 pixels
wide).
`--cycles-pattern SOBOL` renders Cycles with its Sobol-Burley pattern instead of its default PMJ.
"""
import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="two_sphere_noise.py", description=__doc__.splitlines()[0])
    p.add_argument("--objects", type=int, default=2, help="how many of the scene's spheres")
    p.add_argument("--lights", choices=("both", "light", "world"), default="both")
    p.add_argument("--res", type=int, nargs=2, metavar=("W", "H"), default=(256, 80))
    p.add_argument("--spp", type=int, default=64)
    p.add_argument("--seeds", type=int, default=6)
    p.add_argument("--reference-spp", type=int, default=4096)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--cycles-pattern", choices=("PROGRESSIVE_MULTI_JITTER", "SOBOL"), default=None)
    args = p.parse_args(argv)
    for name in ("objects", "spp", "seeds", "reference_spp", "threads"):
        if getattr(args, name) < 1:
            p.error(f"--{name.replace('_', '-')} must be at least 1, got {getattr(args, name)}")
    if min(args.res) < 1:
        p.error(f"--res must be at least 1 x 1, got {args.res}")
    return args


def main():
    args = parse_args()
    if HERE not in sys.path:
        sys.path.insert(0, HERE)
    import side_by_side as sbs

    sbs.use_module_paths()
    import tempfile
    from dataclasses import replace

    import numpy as np

    from compare import scenes

    full = scenes.get("principled_showroom")
    spec = replace(full, objects=full.objects[:args.objects], resolution=tuple(args.res),
                   lights=full.lights if args.lights in ("both", "light") else (),
                   world_color=full.world_color if args.lights in ("both", "world") else (0.0, 0.0, 0.0))
    spec, _ = sbs.set_up_spec(spec)
    work = tempfile.mkdtemp(prefix="bxdf-two-sphere-")
    out = lambda tag: os.path.join(work, f"{tag}.exr")  # noqa: E731
    references = [sbs.render(e, spec, args.reference_spp, 9999, args.threads, out(f"ref_{e}"),
                             args.cycles_pattern)[2] for e in sbs.ENGINES]
    reference = 0.5 * (references[0] + references[1])
    error = {e: np.zeros(reference.shape[:2]) for e in sbs.ENGINES}
    for seed in range(args.seeds):
        for e in sbs.ENGINES:
            image = sbs.render(e, spec, args.spp, seed, args.threads, out(f"{e}_{seed}"),
                               args.cycles_pattern)[2]
            error[e] += ((image - reference) ** 2).mean(axis=2) / args.seeds
    os.rmdir(work)
    mse = {e: float(error[e].mean()) for e in sbs.ENGINES}
    # The same ratio without the 1% of pixels where the engines' errors differ most.
    difference = np.abs(error["BXDF_LAB"] - error["CYCLES"]).ravel()
    keep = np.ones(difference.size, dtype=bool)
    keep[np.argsort(difference)[::-1][:max(1, difference.size // 100)]] = False
    rest = {e: float(error[e].ravel()[keep].mean()) for e in sbs.ENGINES}
    print(f"two_sphere_noise: {args.objects} spheres, lights {args.lights}, {args.res[0]}x{args.res[1]}, "
          f"{args.spp} spp x {args.seeds} seeds, reference {args.reference_spp} spp, Cycles pattern "
          f"{args.cycles_pattern or 'the harness default'}")
    print(f"  MSE BXDF_LAB {mse['BXDF_LAB']:.3e}  Cycles {mse['CYCLES']:.3e}  ratio "
          f"{mse['BXDF_LAB'] / mse['CYCLES']:.2f}")
    print(f"  without the 1% of pixels where they differ most: ratio "
          f"{rest['BXDF_LAB'] / rest['CYCLES']:.2f}")


if __name__ == "__main__":
    if ROOT not in sys.path:
        sys.path.insert(0, ROOT)
    from compare import blender_main
    blender_main.run(main)
