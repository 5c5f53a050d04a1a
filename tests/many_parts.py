#!/usr/bin/env python3
"""many_parts.py OUT.obj|OUT.gltf [PARTS [MATERIALS]]: a model with many parts (tests/many_parts.sh,
the assembly benchmark in docs/cli.md). PARTS (default 1331) squares, one component each
(OBJ: g/usemtl part_I; glTF: node, mesh and material part_I; component index I), on a
grid ceil(sqrt(PARTS)) wide; each square overlaps its neighbours and sits at its own
depth (I mod 5), so neighbours overlap at distinct depths. Parts PARTS-131 and PARTS-31
(1200 and 1300 of 1331) are large squares in front, overlapping each other and the
grid: changing their opacity changes a large share of the image, so a GPU that ignored
the last parts fails the comparison with the reference by far. The OBJ and the glTF of
one PARTS hold the same parts, names and colours; the glTF (a .gltf and its .bin) hangs
the parts in groups of 1000 under one root node; with MATERIALS, its parts share that
many materials (part I has material I mod MATERIALS, the two front parts their own), as
the parts of a real assembly do."""
import json
import math
import os
import struct
import sys

out = sys.argv[1]
parts = int(sys.argv[2]) if len(sys.argv) > 2 else 1331
shared = int(sys.argv[3]) if len(sys.argv) > 3 else 0
columns = max(1, math.ceil(math.sqrt(parts)))
scale = columns / 37.0  # 1331 parts: the grid and squares of the original test
front = {parts - 131: (2.0, 2.0, 22.0, 1.5), parts - 31: (14.0, 12.0, 34.0, 2.5)}  # x0, y0, x1, z


def colour(i):
    if i == parts - 131:
        return 0.9, 0.1, 0.1
    if i == parts - 31:
        return 0.1, 0.2, 0.9
    return (0.2 + 0.6 * ((i * 37) % 101) / 100.0, 0.2 + 0.6 * ((i * 59) % 103) / 102.0,
            0.2 + 0.6 * ((i * 83) % 107) / 106.0)


def square(i):
    """The corners (x, y) and the depth of part i."""
    if i in front:
        x0, y0, x1 = (c * scale for c in front[i][:3])
        z = front[i][3]
        x1, y1 = x1, y0 + (x1 - x0)
    else:
        cx, cy = i % columns, i // columns
        x0, y0, x1, y1 = cx - 0.2, cy - 0.2, cx + 1.2, cy + 1.2
        z = -0.05 * (i % 5)
    return [(x0, y0), (x1, y0), (x1, y1), (x0, y1)], z


def write_obj():
    mtl = os.path.splitext(out)[0] + ".mtl"
    with open(mtl, "w") as m:
        for i in range(parts):
            r, g, b = colour(i)
            m.write(f"newmtl part_{i}\nKd {r:.4f} {g:.4f} {b:.4f}\nd 1\nillum 1\n\n")
    with open(out, "w") as f:
        f.write(f"# many_parts.py: {parts} parts\nmtllib {os.path.basename(mtl)}\n")
        vertex = 0
        for i in range(parts):
            corners, z = square(i)
            f.write(f"g part_{i}\nusemtl part_{i}\n")
            for x, y in corners:
                f.write(f"v {x:.3f} {y:.3f} {z:.3f}\n")
            a = vertex + 1
            f.write(f"f {a} {a + 1} {a + 2}\nf {a} {a + 2} {a + 3}\n")
            vertex += 4


def write_gltf():
    # the OBJ's numbers as written there (3 decimals), as float32
    positions, indices = bytearray(), bytearray()
    for i in range(parts):
        corners, z = square(i)
        for x, y in corners:
            positions += struct.pack("<3f", round(x, 3), round(y, 3), round(z, 3))
        indices += struct.pack("<6I", 0, 1, 2, 0, 2, 3)
    bin_name = os.path.splitext(os.path.basename(out))[0] + ".bin"
    with open(os.path.join(os.path.dirname(out) or ".", bin_name), "wb") as b:
        b.write(positions + indices)
    accessors, meshes, materials, nodes = [], [], [], []
    groups = math.ceil(parts / 1000)
    nodes.append({"name": "assembly", "children": list(range(1, groups + 1))})
    for g in range(groups):
        first = 1 + groups + g * 1000
        nodes.append({"name": f"group_{g}", "children": list(range(first, min(first + 1000, 1 + groups + parts)))})
    for i in range(parts):
        corners, z = square(i)
        xs = [round(x, 3) for x, _ in corners]
        ys = [round(y, 3) for _, y in corners]
        zr = round(z, 3)
        accessors.append({"bufferView": 0, "byteOffset": i * 48, "componentType": 5126, "count": 4,
                          "type": "VEC3", "min": [min(xs), min(ys), zr], "max": [max(xs), max(ys), zr]})
        accessors.append({"bufferView": 1, "byteOffset": i * 24, "componentType": 5125, "count": 6,
                          "type": "SCALAR"})
        material = i
        if shared and i not in front:
            material = i % shared
        elif shared:
            material = shared + (i == parts - 31)
        meshes.append({"name": f"part_{i}", "primitives": [
            {"attributes": {"POSITION": 2 * i}, "indices": 2 * i + 1, "material": material}]})
        if not shared or i < shared or i in front:
            r, g, b = colour(i)
            materials.append({"name": f"part_{i}", "pbrMetallicRoughness": {
                "baseColorFactor": [round(r, 4), round(g, 4), round(b, 4), 1.0], "metallicFactor": 0.0}})
        nodes.append({"name": f"part_{i}", "mesh": i})
    gltf = {
        "asset": {"version": "2.0", "generator": "tests/many_parts.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": materials,
        "accessors": accessors,
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(positions)},
                        {"buffer": 0, "byteOffset": len(positions), "byteLength": len(indices)}],
        "buffers": [{"byteLength": len(positions) + len(indices), "uri": bin_name}],
    }
    with open(out, "w") as f:
        f.write(json.dumps(gltf, separators=(",", ":")))  # dumps: the C encoder, dump is not


if out.endswith(".gltf"):
    write_gltf()
else:
    write_obj()
