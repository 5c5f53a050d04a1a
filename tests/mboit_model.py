#!/usr/bin/env python3
"""mboit_model.py OIT WORKDIR: mboit's reconstruction against an independent one.

Writes a scene of 8 parallel quads (one colour each, spread over the depth
range, drawn in shuffled order), renders its centre with mboit for each moment
variant and recomputes that pixel here in double precision: the moments of the
quads' optical depths, the biased Hankel (power) or Toeplitz (trigonometric)
reconstruction of the transmittance in front of each quad, and the normalised
composite (docs/algorithms.md, mboit). GPU (float) and this must agree within
1/255 per channel: a wrong step of the reconstruction (a sign, a root, the
interpolation, the bias, the warp) moves the pixel by far more (measured: 8 to
27/255 for the bugs found while writing mboit). The exact composite of the
same pixel is printed beside it, and must differ (the quads are deep enough
for every variant to be an approximation there)."""
import cmath
import json
import math
import os
import random
import struct
import subprocess
import sys
import zlib

OVERESTIMATION = 0.25
ZONE = 0.1 * math.pi
BIAS = {"power4": 5e-7, "power6": 5e-6, "trig3": 8e-7}
BIAS_VECTOR = {"power4": [1, 0, 0.375, 0, 0.375, 0, 0], "power6": [1, 0, 0.48, 0, 0.451, 0, 0.45]}


def interpolate_integral(points, values, moments, mul, div):
    """Integral of the polynomial through (points, values) against moments (Newton, then Horner)."""
    k = len(points)
    f = list(values)
    for level in range(1, k):
        for i in range(k - 1, level - 1, -1):
            f[i] = div(f[i] - f[i - 1], points[i] - points[i - level])
    poly = [f[k - 1]] + [0 * f[0]] * (k - 1)
    for i in range(k - 2, -1, -1):
        poly = [f[i] - mul(points[i], poly[0])] + [poly[j - 1] - mul(points[i], poly[j]) for j in range(1, k)]
    return sum(mul(poly[j], moments[j]) for j in range(k))


def ldl_solve(matrix, rhs, conj):
    """Solve H c = rhs for Hermitian positive definite H by H = L D L^H."""
    k = len(rhs)
    L = [[0] * k for _ in range(k)]
    D = [0.0] * k
    for j in range(k):
        D[j] = (matrix[j][j] - sum(L[j][p] * conj(L[j][p]) * D[p] for p in range(j))).real
        for i in range(j + 1, k):
            L[i][j] = (matrix[i][j] - sum(L[i][p] * conj(L[j][p]) * D[p] for p in range(j))) / D[j]
    c = list(rhs)
    for i in range(k):
        c[i] -= sum(L[i][p] * c[p] for p in range(i))
    c = [c[i] / D[i] for i in range(k)]
    for i in range(k - 1, -1, -1):
        c[i] -= sum(conj(L[p][i]) * c[p] for p in range(i + 1, k))
    return c


def poly_roots(coefficients):
    """Roots of sum_j coefficients[j] t^j by Durand-Kerner (complex, double): independent
    of the shaders' closed forms."""
    n = len(coefficients) - 1
    lead = coefficients[-1]
    a = [c / lead for c in coefficients]
    roots = [(0.4 + 0.9j) ** i for i in range(n)]
    for _ in range(500):
        new = []
        for i, r in enumerate(roots):
            value = sum(a[j] * r ** j for j in range(n + 1))
            denominator = 1
            for j, s in enumerate(roots):
                if j != i:
                    denominator *= r - s
            new.append(r - value / denominator)
        roots = new
    return roots


def absorbance(variant, moments, depth):
    """Normalised absorbance in front of `depth` (warped) from normalised moments."""
    if variant == "trig3":
        m = [moments[0]] + [v * (1 - BIAS[variant]) for v in moments[1:]]
        w = cmath.exp(1j * depth)
        toeplitz = [[m[i - j] if i >= j else m[j - i].conjugate() for j in range(4)] for i in range(4)]
        c = ldl_solve(toeplitz, [w ** i for i in range(4)], lambda z: z.conjugate())
        roots = [r / abs(r) for r in poly_roots([v.conjugate() for v in c])]
        zone_start = 2 * math.pi - ZONE
        values = [OVERESTIMATION]
        for r in roots:
            phase = cmath.phase(r) % (2 * math.pi)
            values.append(1.0 if phase < depth else min(1.0, max(0.0, (phase - zone_start) / ZONE)))
        return interpolate_integral([w] + roots, [complex(v) for v in values], m,
                                    lambda a, b: a * b, lambda a, b: a / b).real
    k = 3 if variant == "power4" else 4
    m = [(1 - BIAS[variant]) * moments[j] + BIAS[variant] * BIAS_VECTOR[variant][j] for j in range(2 * k - 1)]
    hankel = [[m[i + j] for j in range(k)] for i in range(k)]
    c = ldl_solve(hankel, [depth ** i for i in range(k)], lambda z: z)
    roots = [r.real for r in poly_roots(c)]
    values = [OVERESTIMATION] + [1.0 if r < depth else 0.0 for r in roots]
    return interpolate_integral([depth] + roots, values, m, lambda a, b: a * b, lambda a, b: a / b)


def mboit_pixel(variant, layers, background):
    """layers: (s, alpha, rgb). The normalised composite of mboit, in double."""
    optical = [-math.log(1 - a) for s, a, c in layers]
    b0 = sum(optical)
    if variant == "trig3":
        warp = lambda s: s * (2 * math.pi - ZONE)
        moments = [sum(o * cmath.exp(1j * j * warp(s)) for o, (s, a, c) in zip(optical, layers)) / b0
                   for j in range(4)]
    else:
        warp = lambda s: 2 * s - 1
        moments = [sum(o * warp(s) ** j for o, (s, a, c) in zip(optical, layers)) / b0 for j in range(7)]
    num, den = [0.0] * 3, 0.0
    for s, a, c in layers:
        t = min(1.0, max(0.0, math.exp(-b0 * absorbance(variant, moments, warp(s)))))
        num = [num[i] + t * a * c[i] for i in range(3)]
        den += t * a
    total = math.exp(-b0)
    return [num[i] / den * (1 - total) + background[i] * total for i in range(3)]


def exact_pixel(layers, background):
    out, t = [0.0] * 3, 1.0
    for s, a, c in sorted(layers):
        out = [out[i] + t * a * c[i] for i in range(3)]
        t *= 1 - a
    return [out[i] + t * background[i] for i in range(3)]


def png_pixel(path, x, y):
    data = open(path, "rb").read()
    pos, idat = 8, b""
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour_type = struct.unpack(">IIBB", body[:10])
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    assert depth == 8 and colour_type in (2, 6), "8-bit RGB(A) PNG expected"
    raw, bpp = zlib.decompress(idat), (4 if colour_type == 6 else 3)
    stride, previous, i = width * bpp, bytearray(width * bpp), 0
    for row in range(height):
        kind, line = raw[i], bytearray(raw[i + 1:i + 1 + stride])
        i += 1 + stride
        for k in range(stride):
            a = line[k - bpp] if k >= bpp else 0
            b, c = previous[k], (previous[k - bpp] if k >= bpp else 0)
            if kind == 1:
                line[k] = (line[k] + a) & 255
            elif kind == 2:
                line[k] = (line[k] + b) & 255
            elif kind == 3:
                line[k] = (line[k] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[k] = (line[k] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        if row == y:
            return tuple(line[x * bpp:x * bpp + 3])
        previous = line


def write_quads(work, depths, colours):
    """Parallel 2x2 quads at z = depths, one colour each, in that order (the draw order): an OBJ and
    its MTL in work. Returns the OBJ's path."""
    obj, mtl = os.path.join(work, "quads.obj"), os.path.join(work, "quads.mtl")
    with open(mtl, "w") as f:
        for i, c in enumerate(colours):
            f.write(f"newmtl m{i}\nKd {c[0]:.6f} {c[1]:.6f} {c[2]:.6f}\nd 1\n")
    with open(obj, "w") as f:
        f.write("mtllib quads.mtl\n")
        for i, z in enumerate(depths):
            f.write(f"o quad{i}\nusemtl m{i}\n")
            for x, y in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                f.write(f"v {x} {y} {z}\n")
            f.write(f"f {4 * i + 1} {4 * i + 2} {4 * i + 3}\nf {4 * i + 1} {4 * i + 3} {4 * i + 4}\n")
    return obj


def render_centre_layers(oit, obj, algorithm, png, depths, colours, alpha):
    """Renders obj at 16x16, flat, every part at alpha, with `oit render --algorithm ALGORITHM...`
    into png. Returns (layers, None): each quad's (canonical depth s, alpha, rgb) at the centre
    pixel, s = (eye depth - near) / (far - near) from --json's matrices (printed row by row);
    or (None, the error)."""
    run = subprocess.run([oit, "render", "--model", obj, "--algorithm", *algorithm, "--size", "16x16",
                          "--shading", "flat", "--alpha", str(alpha), "--out", png, "--json", "--debug"],
                         capture_output=True, text=True)
    if run.returncode != 0:
        return None, f"render exited {run.returncode}: {run.stderr.strip()}"
    frame = json.loads(run.stdout)
    modelview, projection = frame["modelview"], frame["projection"]
    near = projection[11] / (projection[10] - 1)
    far = projection[11] / (projection[10] + 1)
    return [((-(z + modelview[11]) - near) / (far - near), alpha, c) for z, c in zip(depths, colours)], None


def main():
    oit, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    rng = random.Random(3)
    depths = [-3 + 6 * i / 7 for i in range(8)]
    rng.shuffle(depths)
    colours = [(rng.random(), rng.random(), rng.random()) for _ in depths]
    obj = write_quads(work, depths, colours)
    alpha, background, failed = 0.5, (1.0, 1.0, 1.0), False
    for variant in ("power4", "power6", "trig3"):
        png = os.path.join(work, f"{variant}.png")
        layers, error = render_centre_layers(oit, obj, ["mboit", "--moments", variant], png, depths, colours, alpha)
        if error:
            print(f"FAIL: {variant}: {error}")
            return 1
        model = [round(255 * v) for v in mboit_pixel(variant, layers, background)]
        exact = [round(255 * v) for v in exact_pixel(layers, background)]
        gpu = list(png_pixel(png, 8, 8))
        worst = max(abs(g - m) for g, m in zip(gpu, model))
        off_exact = max(abs(m - e) for m, e in zip(model, exact))
        ok = worst <= 1 and off_exact > 1
        failed |= not ok
        print(f"{'ok' if ok else 'FAIL'}: {variant}: gpu {gpu}, double-precision mboit {model} "
              f"(off by {worst}, at most 1), exact composite {exact} (mboit off by {off_exact})")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
