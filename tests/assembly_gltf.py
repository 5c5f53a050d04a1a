#!/usr/bin/env python3
"""assembly_gltf.py OUT.gltf: a small glTF 2.0 gearbox with an assembly tree,
and the parts' names and paths it must import as (printed as JSON, in the
components' order).

  gearbox                       the scene's single top node (Assimp's root)
    housing                     a node holding one mesh "housing": the part itself
    input_shaft
      shaft                     mesh "shaft"
      bearing_1, bearing_2      one mesh "bearing" instanced twice: named after the nodes
    output_shaft
      (unnamed node)            hands its contents to output_shaft
        shaft                   a second mesh "shaft": the part "shaft#2"
      stage, stage              two sibling nodes of one name: "stage", "stage#2"
        pinion                  a node holding a mesh "pinion_mesh" (not its name): a node
      cover                     a mesh named "cover" beside a node named "cover":
      cover                       the node becomes "cover#2"
        bolt_1                  mesh "bolt", used once: a node holding part "bolt"
Each part is a box of its own place, so that hiding any changes the image."""
import base64
import json
import struct
import sys

out = sys.argv[1]

# one unit box, 8 corners, 12 triangles
corners = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
triangles = [i for a, b, c, d in quads for i in (a, b, c, a, c, d)]
data = b"".join(struct.pack("<3f", *c) for c in corners) + struct.pack("<36H", *triangles)

meshes, materials = [], []


def mesh(name, colour):
    materials.append({"pbrMetallicRoughness": {"baseColorFactor": colour + [0.6]}})
    meshes.append({"name": name, "primitives": [{"attributes": {"POSITION": 0}, "indices": 1,
                                                   "material": len(materials) - 1}]})
    return len(meshes) - 1


housing = mesh("housing", [0.6, 0.6, 0.7])
shaft = mesh("shaft", [0.8, 0.2, 0.2])
bearing = mesh("bearing", [0.2, 0.8, 0.2])
shaft2 = mesh("shaft", [0.8, 0.4, 0.2])
pinion = mesh("pinion_mesh", [0.2, 0.2, 0.8])
pinion2 = mesh("pinion_mesh", [0.2, 0.4, 0.8])
cover = mesh("cover", [0.7, 0.7, 0.2])
bolt = mesh("bolt", [0.5, 0.5, 0.5])

nodes = []


def node(name, children=(), mesh=None, at=(0, 0, 0), scale=1.0):
    n = {"children": list(children)} if children else {}
    if name is not None:
        n["name"] = name
    if mesh is not None:
        n["mesh"] = mesh
    n["translation"] = list(at)
    if scale != 1.0:
        n["scale"] = [scale] * 3
    nodes.append(n)
    return len(nodes) - 1


h = node("housing", mesh=housing, at=(0, 0, 0), scale=0.9)
s1 = node("shaft", mesh=shaft, at=(1, 0, 0), scale=0.8)
b1 = node("bearing_1", mesh=bearing, at=(2, 0, 0), scale=0.7)
b2 = node("bearing_2", mesh=bearing, at=(3, 0, 0), scale=0.7)
inp = node("input_shaft", [s1, b1, b2], at=(0, 1, 0))
s2 = node("shaft", mesh=shaft2, at=(0, 0, 0), scale=0.8)
wrap = node(None, [s2], at=(1, 0, 0))
p1 = node("pinion", mesh=pinion, at=(2, 0, 0), scale=0.6)
p2 = node("pinion", mesh=pinion2, at=(3, 0, 0), scale=0.6)
st1 = node("stage", [p1])
st2 = node("stage", [p2], at=(0, 0, 1))
c = node("cover", mesh=cover, at=(0, 0, 2), scale=0.9)
bolt1 = node("bolt_1", mesh=bolt, at=(1, 0, 2), scale=0.5)
cn = node("cover", [bolt1])
out_ = node("output_shaft", [wrap, st1, st2, c, cn], at=(0, 2, 0))
top = node("gearbox", [h, inp, out_])

gltf = {
    "asset": {"version": "2.0"},
    "scene": 0,
    "scenes": [{"nodes": [top]}],
    "nodes": nodes,
    "meshes": meshes,
    "materials": materials,
    "buffers": [{"byteLength": len(data),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 96},
                    {"buffer": 0, "byteOffset": 96, "byteLength": 72}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 1]},
                  {"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"}],
}
with open(out, "w") as f:
    json.dump(gltf, f)

# What the import must give, depth first, children in order (the parts'
# order without a tree): name and path.
expected = [
    ("housing", "gearbox/housing"),
    ("shaft", "gearbox/input_shaft/shaft"),
    ("bearing_1", "gearbox/input_shaft/bearing_1"),
    ("bearing_2", "gearbox/input_shaft/bearing_2"),
    ("shaft#2", "gearbox/output_shaft/shaft#2"),
    ("pinion_mesh", "gearbox/output_shaft/stage/pinion/pinion_mesh"),
    ("pinion_mesh#2", "gearbox/output_shaft/stage#2/pinion/pinion_mesh#2"),
    ("cover", "gearbox/output_shaft/cover"),
    ("bolt", "gearbox/output_shaft/cover#2/bolt_1/bolt"),
]
print(json.dumps(expected))
