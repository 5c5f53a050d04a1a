#!/usr/bin/env python3
"""mlab_precision.py: is 16-bit layer storage enough for mlab's merge chains?

Runs mlab's insert / merge / resolve (src/core/alg_mlab.c, shaders/mlab/) on
random fragment lists twice: once rounding every layer write to 16-bit unorm,
as packUnorm2x16 does, and once in float64. Prints the worst difference of
the resolved colour (white background) per k, in 1/255 units. Lists have k+1
to 64 fragments (so every list merges), alphas 0.05, 0.5 or uniform in [0, 1],
random colours and depths; every other list arrives in depth order.

    python3 bat/mlab_precision.py
"""
import random, sys
def q(x): return round(min(max(x, 0.0), 1.0) * 65535.0) / 65535.0
def run(frags, k, quant):
    L = []  # (c, t, key) sorted by key
    Q = (lambda v: q(v)) if quant else (lambda v: v)
    for (c, a, key) in frags:
        f = ([Q(x * a) for x in c], Q(1 - a), key)
        p = sum(1 for l in L if l[2] < key)
        L.insert(p, f)
        if len(L) > k:
            (ca, ta, ka), (cb, tb, kb) = L[-2], L[-1]
            L[-2:] = [([Q(ca[i] + ta * cb[i]) for i in range(3)], Q(ta * tb), ka)]
    C, T = [0.0] * 3, 1.0
    for (c, t, key) in L:
        C = [C[i] + T * c[i] for i in range(3)]; T *= t
    return [C[i] + T * 1.0 for i in range(3)]  # white background
random.seed(1)
for k in (1, 4, 8, 16):
    worst = 0.0
    for trial in range(3000):
        n = random.randint(k + 1, 64)
        frags = [([random.random() for _ in range(3)], random.choice([0.5, random.random(), 0.05]),
                  random.random()) for _ in range(n)]
        if trial % 2:  # back to front arrival: every fragment merges into the last layer
            frags.sort(key=lambda f: f[2])
        a, b = run(frags, k, True), run(frags, k, False)
        worst = max(worst, max(abs(a[i] - b[i]) for i in range(3)) * 255)
    print(f"k={k}: worst |16-bit - float| over 3000 lists of k+1..64 fragments: {worst:.4f}/255")
