#!/usr/bin/env python3
"""wavelet_model.py OIT WORKDIR: wavelet's reconstruction against an independent one.

Writes a scene of 8 parallel quads (one colour each, drawn in shuffled order;
two pairs of them close together in depth, so that they share a bin at every
rank), renders its centre with wavelet at ranks 1, 2 and 3 and recomputes that
pixel here in double precision without any wavelet: the Haar projection of rank
R is the absorbance's mean over each of the N = 2^(R+1) bins, so the model
integrates the other quads' absorbance steps over the bins directly, interpolates
the means as shaders/wavelet/common.glsl (W4) says and composites as mboit does.
GPU (float, through the Haar coefficients) and this must agree within 1/255 per
channel: a wrong coefficient, sign, level or bin index moves the pixel by far
more. The exact composite is printed beside it; rank 1 must differ from it (two
quads per bin at least), so the check is not of a case where any T would do."""
import math
import os
import random
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mboit_model import exact_pixel, png_pixel, render_centre_layers, write_quads  # noqa: E402  (shared set-up)


def bin_means(steps, bins):
    """steps: (s, optical depth). The mean of sum a H(z - s) over each of `bins` bins of [0, 1)."""
    width = 1.0 / bins
    means = []
    for b in range(bins):
        low, high = b * width, (b + 1) * width
        means.append(sum(a * max(0.0, high - max(low, s)) for s, a in steps) / width)
    return means


def wavelet_pixel(rank, layers, background):
    """layers: (s, alpha, rgb). wavelet's composite (W1..W5), in double, from bin means."""
    bins = 2 << rank
    optical = [-math.log(1 - a) for s, a, c in layers]
    num, den = [0.0] * 3, 0.0
    for i, (s, a, c) in enumerate(layers):
        others = [(layers[j][0], optical[j]) for j in range(len(layers)) if j != i]
        means = bin_means(others, bins)
        b = min(int(math.floor(s * bins)), bins - 1)
        f = min(1.0, max(0.0, s * bins - b))
        before = means[b - 1] if b > 0 else 0.0
        t = math.exp(-((1 - f) * before + f * means[b]))
        num = [num[k] + t * a * c[k] for k in range(3)]
        den += t * a
    total = math.exp(-sum(optical))
    return [num[k] / den * (1 - total) + background[k] * total for k in range(3)]


def main():
    oit, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    rng = random.Random(5)
    # z in [-3, 3]; two pairs 0.05 apart (well inside the narrowest bin, 1/16 of the depth range)
    depths = [-3.0, -2.1, -1.0, -0.95, 0.4, 1.3, 2.6, 2.65]
    rng.shuffle(depths)
    colours = [(rng.random(), rng.random(), rng.random()) for _ in depths]
    obj = write_quads(work, depths, colours)
    alpha, background, failed = 0.5, (1.0, 1.0, 1.0), False
    for rank in (1, 2, 3):
        png = os.path.join(work, f"rank{rank}.png")
        layers, error = render_centre_layers(oit, obj, ["wavelet", "--wavelet-rank", str(rank)], png, depths,
                                             colours, alpha)
        if error:
            print(f"FAIL: rank {rank}: {error}")
            return 1
        model = [round(255 * v) for v in wavelet_pixel(rank, layers, background)]
        exact = [round(255 * v) for v in exact_pixel(layers, background)]
        gpu = list(png_pixel(png, 8, 8))
        worst = max(abs(g - m) for g, m in zip(gpu, model))
        off_exact = max(abs(m - e) for m, e in zip(model, exact))
        ok = worst <= 1 and (rank != 1 or off_exact > 1)
        failed |= not ok
        print(f"{'ok' if ok else 'FAIL'}: rank {rank}: gpu {gpu}, double-precision wavelet {model} "
              f"(off by {worst}, at most 1), exact composite {exact} (wavelet off by {off_exact}); "
              f"depths s {sorted(round(l[0], 4) for l in layers)}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
