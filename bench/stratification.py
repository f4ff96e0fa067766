"""Whether an engine's extra error at N samples comes from its samples or from how it spreads them.

    blender -b --factory-startup --python-exit-code 1 --python bench/stratification.py -- \\
        --scene sweep_principled_transmission --spp 64 --renders 300 --single-renders 3000

Renders a harness scene with both engines (set up as bench/side_by_side.py sets them up, 2
threads): `--single-renders` one-sample renders and `--renders` renders of `--spp` samples per
engine, alternating engines, each with its own seed. From the one-sample renders it takes each
pixel's per-sample variance V1; from the N-sample renders their variance VN about their own mean
(no reference needed, so no reference noise). Independent samples would give VN = V1 / N;
a sampler whose samples are stratified within the pixel gives less, so VN / (V1 / N) is what the
engine's sampling pattern gains there (1: nothing). Variances are per channel, averaged over the
image as side_by_side.py's MSE is.

A render's error is heavy-tailed where caustics and glossy paths meet a small light: a few
samples in millions hold much of it, so tens of renders leave the engines' ratio uncertain by
10-20%; hundreds of N-sample renders and thousands of one-sample renders (each engine's pixels
then have as many samples as in the N-sample renders together) are what separates a per-sample
difference from a stratification one. Also reports how many one-sample values exceed 10, 30 and
100 (the tails), the per-sample variance of the values clipped at those thresholds (the body of
the distribution, which a few extreme samples cannot sway: equal bodies and equal tail counts
mean the engines draw the same distribution, and a difference in V1 is the extreme tail), and
the mean images' difference (their bias against each other, plus noise).
"""
import argparse
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import side_by_side  # noqa: E402

TAIL_THRESHOLDS = (10.0, 30.0, 100.0)


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="stratification.py", description=__doc__.splitlines()[0])
    p.add_argument("--scene", default="sweep_principled_transmission",
                   help="harness scene name (compare/scenes.py)")
    p.add_argument("--spp", type=int, default=64, help="samples of the N-sample renders")
    p.add_argument("--renders", type=int, default=300, help="N-sample renders per engine")
    p.add_argument("--single-renders", type=int, default=3000,
                   help="one-sample renders per engine")
    p.add_argument("--first-seed", type=int, default=0,
                   help="the one-sample renders take seeds first-seed.., the N-sample renders "
                        "the seeds after them")
    p.add_argument("--threads", type=int, default=2, help="threads for both engines")
    args = p.parse_args(argv)
    if args.first_seed < 0:
        p.error(f"--first-seed must be at least 0, got {args.first_seed}")
    if args.spp < 2:
        p.error(f"--spp must be at least 2, got {args.spp}")
    for name in ("renders", "single_renders"):
        if getattr(args, name) < 2:
            p.error(f"--{name.replace('_', '-')} must be at least 2, got {getattr(args, name)}")
    if args.threads < 1:
        p.error(f"--threads must be at least 1, got {args.threads}")
    return args


class Moments:
    """Per-pixel, per-channel sums of renders, for their mean and (unbiased) variance."""

    def __init__(self):
        self.count = 0
        self.sum = self.sum_sq = None
        self.tails = [0] * len(TAIL_THRESHOLDS)
        self.clipped = [None] * len(TAIL_THRESHOLDS)  # Moments of the values clipped there

    def add(self, image, one_sample=False):
        """Adds a render; `one_sample` (a one-sample render) also counts its values above the
        tail thresholds and adds them clipped there, which mean something only per sample."""
        import numpy as np

        x = np.asarray(image[..., :3], dtype=np.float64)
        if self.sum is None:
            self.sum, self.sum_sq = np.zeros_like(x), np.zeros_like(x)
        self.count += 1
        self.sum += x
        self.sum_sq += x * x
        if one_sample:
            for i, t in enumerate(TAIL_THRESHOLDS):
                self.tails[i] += int((x > t).sum())
                if self.clipped[i] is None:
                    self.clipped[i] = Moments()
                self.clipped[i].add(np.minimum(x, t))

    def mean(self):
        return self.sum / self.count

    def variance(self):
        m = self.mean()
        return (self.sum_sq / self.count - m * m) * (self.count / (self.count - 1))


def main():
    args = parse_args()
    side_by_side.use_module_paths()

    spec, _ = side_by_side.set_up_scene(args.scene, None)
    engines = side_by_side.ENGINES
    work = tempfile.mkdtemp(prefix="bxdf-stratification-")
    single = {e: Moments() for e in engines}
    many = {e: Moments() for e in engines}
    seed = args.first_seed
    for moments, spp, renders in ((single, 1, args.single_renders), (many, args.spp, args.renders)):
        for _ in range(renders):
            for e in engines:
                image = side_by_side.render(e, spec, spp, seed, args.threads,
                                            os.path.join(work, f"{e}.exr"))[2]
                moments[e].add(image, one_sample=spp == 1)
            seed += 1
    os.rmdir(work)

    print(f"stratification: {args.scene}, {args.threads} threads; per engine "
          f"{args.single_renders} one-sample renders and {args.renders} at {args.spp} spp "
          f"(seeds {args.first_seed}-{seed - 1})")
    print(f"  {'engine':<9} {'V1':>10} {'V1/N':>10} {'VN':>10} {'VN/(V1/N)':>10}   one-sample "
          "values above " + ", ".join(f"{t:g}" for t in TAIL_THRESHOLDS))
    v1 = {e: float(single[e].variance().mean()) for e in engines}
    vn = {e: float(many[e].variance().mean()) for e in engines}
    for e in engines:
        print(f"  {e:<9} {v1[e]:>10.4g} {v1[e] / args.spp:>10.4g} {vn[e]:>10.4g} "
              f"{vn[e] / (v1[e] / args.spp):>10.3f}   {', '.join(map(str, single[e].tails))}")
    a, b = engines
    clipped = {e: [float(m.variance().mean()) for m in single[e].clipped] for e in engines}
    print("  per-sample variance of the one-sample values clipped at "
          + ", ".join(f"{t:g}" for t in TAIL_THRESHOLDS) + f" ({a}/{b}): "
          + ", ".join(f"{clipped[a][i]:.4g}/{clipped[b][i]:.4g} = {clipped[a][i] / clipped[b][i]:.3f}"
                      for i in range(len(TAIL_THRESHOLDS))))
    difference = many[a].mean() - many[b].mean()
    print(f"  {a}/{b}: per-sample variance {v1[a] / v1[b]:.3f}, variance at {args.spp} spp "
          f"{vn[a] / vn[b]:.3f}; the mean images' squared difference "
          f"{float((difference ** 2).mean()):.3g} (their variances' sum over "
          f"{args.renders} renders: {(vn[a] + vn[b]) / args.renders:.3g})")


if __name__ == "__main__":
    main()
