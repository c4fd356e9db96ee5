#!/usr/bin/env python3
"""Writes MorphInterpolation.gltf: a small glTF 2.0 file that exercises what the
Khronos morph samples do not: STEP and CUBICSPLINE weights, weights outside
[0, 1], node weights overriding mesh weights, a sparse target without a
bufferView, and a skinned mesh with morph targets (morphed first, then
skinned). Every target has POSITION: three.js r187's GLTFLoader morphs by the
base positions themselves where a target lacks POSITION (wrong for relative
targets), so a NORMAL-only target would make its reference poses wrong. Run it again to regenerate the file:

    python3 make_morph_model.py > MorphInterpolation.gltf
"""
import base64
import json
import struct

FLOAT, USHORT, UBYTE = 5126, 5123, 5121


class Builder:
    def __init__(self):
        self.data = bytearray()
        self.views = []
        self.accessors = []

    def view(self, raw):
        while len(self.data) % 4:
            self.data.append(0)
        self.views.append({"buffer": 0, "byteOffset": len(self.data), "byteLength": len(raw)})
        self.data += raw
        return len(self.views) - 1

    def accessor(self, values, kind, ctype=FLOAT, minmax=False):
        size = {"SCALAR": 1, "VEC3": 3, "VEC4": 4, "MAT4": 16}[kind]
        fmt = {FLOAT: "f", USHORT: "H", UBYTE: "B"}[ctype]
        flat = [x for v in values for x in (v if isinstance(v, (list, tuple)) else [v])]
        acc = {"bufferView": self.view(struct.pack("<%d%s" % (len(flat), fmt), *flat)),
               "componentType": ctype, "count": len(values), "type": kind}
        if minmax:
            acc["min"] = [min(flat[i::size]) for i in range(size)]
            acc["max"] = [max(flat[i::size]) for i in range(size)]
        self.accessors.append(acc)
        return len(self.accessors) - 1

    def sparse_zero(self, count, indices, values):
        """A VEC3 accessor without a bufferView: zeros, with `values` at `indices`."""
        iv = self.view(struct.pack("<%dH" % len(indices), *indices))
        flat = [x for v in values for x in v]
        vv = self.view(struct.pack("<%df" % len(flat), *flat))
        # glTF wants bounds on POSITION targets; the zeros count too.
        low = [min([0.0] + [v[i] for v in values]) for i in range(3)]
        high = [max([0.0] + [v[i] for v in values]) for i in range(3)]
        self.accessors.append({"componentType": FLOAT, "count": count, "type": "VEC3", "min": low, "max": high,
                               "sparse": {"count": len(indices),
                                          "indices": {"bufferView": iv, "componentType": USHORT},
                                          "values": {"bufferView": vv}}})
        return len(self.accessors) - 1


b = Builder()
quad = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
up = [(0, 0, 1)] * 4
indices = b.accessor([0, 1, 2, 0, 2, 3], "SCALAR", USHORT)
position = b.accessor(quad, "VEC3", minmax=True)
normal = b.accessor(up, "VEC3")
t0 = b.accessor([(0, 0, 0.5), (0, 0, 0.5), (0, 0, 0), (0, 0, 0)], "VEC3", minmax=True)
t0n = b.accessor([(0.6, 0, -0.2), (0.6, 0, -0.2), (0, 0, 0), (0, 0, 0)], "VEC3")
t1 = b.sparse_zero(4, [1, 3], [(0.25, 0, 0), (0, -0.5, 0.25)])
t2 = b.accessor([(0, 0, 0.1), (0, 0, -0.1), (0.1, 0, 0), (0, 0.2, 0)], "VEC3", minmax=True)
t2n = b.accessor([(0, 0.3, 0)] * 4, "VEC3")

# A strip of two joints for the skinned mesh: 6 vertices up the y axis.
strip = [(x, y, 0) for y in (0, 1, 2) for x in (0, 0.5)]
skin_pos = b.accessor(strip, "VEC3", minmax=True)
skin_idx = b.accessor([0, 1, 3, 0, 3, 2, 2, 3, 5, 2, 5, 4], "SCALAR", USHORT)
joints = b.accessor([(0, 0, 0, 0)] * 2 + [(0, 1, 0, 0)] * 2 + [(1, 0, 0, 0)] * 2, "VEC4", UBYTE)
weights = b.accessor([(1, 0, 0, 0)] * 2 + [(0.5, 0.5, 0, 0)] * 2 + [(1, 0, 0, 0)] * 2, "VEC4")
skin_t0 = b.accessor([(0.2, 0, 0)] * 6, "VEC3", minmax=True)
skin_t1 = b.accessor([(0, 0, 0), (0, 0, 0), (0, 0, 0.3), (0, 0, 0.3), (0, 0.4, 0), (0, 0.4, 0)], "VEC3", minmax=True)
ibm = b.accessor([[1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1],
                  [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1]], "MAT4")

times3 = b.accessor([0.0, 1.0, 2.0], "SCALAR", minmax=True)
step_w = b.accessor([0, 0, 0, 1.5, 0, 0.5, -0.25, 1, 1], "SCALAR")
linear_w = b.accessor([0, 0, 0, 1, 0.5, 0, 0.25, 1.5, 1], "SCALAR")
linear_skin_w = b.accessor([0, 0, 1, 0.5, 0.5, 1], "SCALAR")
# CUBICSPLINE: per key, 3 in-tangents, 3 values, 3 out-tangents.
cubic_w = b.accessor([0, 0, 0, 0, 0, 0, 2, -1, 0.5,
                      -1, 1, 0, 1, 0.25, 0, 0.5, 3, -2,
                      1, 0, 0, 0.5, 1, 1, 0, 0, 0], "SCALAR")
cubic_skin_w = b.accessor([0, 0, 0, 0, 1, 1,
                           2, -2, 1, 0.5, 0, 0,
                           0, 0, 0, 0, 0, 0], "SCALAR")
rot = b.accessor([(0, 0, 0, 1), (0, 0, 0.3826834, 0.9238795), (0, 0, 0, 1)], "VEC4")

doc = {
    "asset": {"version": "2.0", "generator": "make_morph_model.py (engine tests)"},
    "scene": 0,
    "scenes": [{"nodes": [0, 1, 2, 3]}],
    "nodes": [
        {"name": "override", "mesh": 0, "weights": [1, 0, 0.5], "translation": [-2, 0, 0]},
        {"name": "animated", "mesh": 0, "translation": [2, 0, 0], "rotation": [0, 0.3826834, 0, 0.9238795]},
        {"name": "skinned", "mesh": 1, "skin": 0, "translation": [10, 10, 10]},
        {"name": "root", "children": [4], "translation": [0, 0, -1]},
        {"name": "tip", "translation": [0, 1, 0]},
    ],
    "meshes": [
        {"name": "quad", "weights": [0.25, 0, 0.5],
         "primitives": [{"attributes": {"POSITION": position, "NORMAL": normal}, "indices": indices,
                         "targets": [{"POSITION": t0, "NORMAL": t0n}, {"POSITION": t1}, {"POSITION": t2, "NORMAL": t2n}]}]},
        {"name": "strip",
         "primitives": [{"attributes": {"POSITION": skin_pos, "JOINTS_0": joints, "WEIGHTS_0": weights},
                         "indices": skin_idx, "targets": [{"POSITION": skin_t0}, {"POSITION": skin_t1}]}]},
    ],
    "skins": [{"joints": [3, 4], "inverseBindMatrices": ibm, "skeleton": 3}],
    "animations": [
        {"name": "Step", "channels": [{"sampler": 0, "target": {"node": 1, "path": "weights"}}],
         "samplers": [{"input": times3, "output": step_w, "interpolation": "STEP"}]},
        {"name": "Linear",
         "channels": [{"sampler": 0, "target": {"node": 1, "path": "weights"}},
                      {"sampler": 1, "target": {"node": 2, "path": "weights"}},
                      {"sampler": 2, "target": {"node": 4, "path": "rotation"}}],
         "samplers": [{"input": times3, "output": linear_w},
                      {"input": times3, "output": linear_skin_w},
                      {"input": times3, "output": rot}]},
        {"name": "CubicSpline",
         "channels": [{"sampler": 0, "target": {"node": 1, "path": "weights"}},
                      {"sampler": 1, "target": {"node": 2, "path": "weights"}}],
         "samplers": [{"input": times3, "output": cubic_w, "interpolation": "CUBICSPLINE"},
                      {"input": times3, "output": cubic_skin_w, "interpolation": "CUBICSPLINE"}]},
    ],
    "buffers": [{"byteLength": len(b.data),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(b.data)).decode()}],
    "bufferViews": b.views,
    "accessors": b.accessors,
}
print(json.dumps(doc, indent=1))
