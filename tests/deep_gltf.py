#!/usr/bin/env python3
"""deep_gltf.py DEPTH OUT.gltf: a valid glTF 2.0 file whose two triangles hang
in two nodes: one at the root, one at the end of a chain of DEPTH nested
nodes (each translating by 1/DEPTH along x). Checks that import walks node
trees of any depth."""
import base64
import json
import struct
import sys

depth, out = int(sys.argv[1]), sys.argv[2]
positions = [0, 0, 0, 1, 0, 0, 0, 1, 0]
data = struct.pack("<9f", *positions) + struct.pack("<3H", 0, 1, 2) + b"\0\0"
nodes = [{"name": "near", "mesh": 0, "children": [1]}]
for level in range(depth):
    node = {"name": "level%d" % level, "translation": [1.0 / depth, 0, 0]}
    if level + 1 < depth:
        node["children"] = [len(nodes) + 1]
    else:
        node["mesh"] = 1
    nodes.append(node)
gltf = {
    "asset": {"version": "2.0"},
    "scene": 0,
    "scenes": [{"nodes": [0]}],
    "nodes": nodes,
    "meshes": [{"name": name, "primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}
               for name in ("near", "far")],
    "buffers": [{"byteLength": len(data),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                    {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
}
with open(out, "w") as f:
    json.dump(gltf, f)
