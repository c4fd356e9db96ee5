#!/usr/bin/env python3
"""Writes the fuzzers' seed corpus (corpus/<target>/): tiny models, scenes and
PNGs made here from scratch, so the seeds are the project's own and reproducible.
Run it again after changing it; the files are committed.

Usage: tests/fuzz/make_corpus.py
"""
import base64
import json
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def out(target, name, data):
    folder = os.path.join(HERE, "corpus", target)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


# --- PNG ------------------------------------------------------------------------

def png(width, height, color_type, bit_depth, rows, palette=None, interlace=0):
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    raw = b"".join(b"\x00" + r for r in rows)  # filter 0 on every row
    data = b"\x89PNG\r\n\x1a\n"
    data += chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, bit_depth, color_type, 0, 0, interlace))
    if palette:
        data += chunk(b"PLTE", b"".join(bytes(c) for c in palette))
    data += chunk(b"IDAT", zlib.compress(raw))
    data += chunk(b"IEND", b"")
    return data


def write_pngs():
    out("png", "rgba_2x2.png", png(2, 2, 6, 8, [bytes([255, 0, 0, 255, 0, 255, 0, 128])] * 2))
    out("png", "rgb_3x2.png", png(3, 2, 2, 8, [bytes(range(9)), bytes(range(9, 18))]))
    out("png", "grey_4x1.png", png(4, 1, 0, 8, [bytes([0, 64, 128, 255])]))
    out("png", "grey16_2x2.png", png(2, 2, 0, 16, [bytes([0, 1, 255, 255])] * 2))
    out("png", "grey_alpha_1x1.png", png(1, 1, 4, 8, [bytes([200, 100])]))
    out("png", "palette_8x1.png", png(8, 1, 3, 1, [bytes([0b10110010])], palette=[(0, 0, 0), (255, 255, 0)]))
    out("png", "rgba16_1x1.png", png(1, 1, 6, 16, [bytes(8)]))
    # A heightmap-like ramp, the kind of image the terrain reads.
    out("png", "height_16x16.png", png(16, 16, 0, 8, [bytes((x + y) * 8 for x in range(16)) for y in range(16)]))


# --- glTF -----------------------------------------------------------------------

class Model:
    """A small skinned, animated model built accessor by accessor."""

    def __init__(self):
        self.bin = bytearray()
        self.views = []
        self.accessors = []

    def add(self, fmt, values, component_type, type_, count, target=None, minmax=None, normalized=False):
        while len(self.bin) % 4:
            self.bin.append(0)
        offset = len(self.bin)
        self.bin += struct.pack("<" + fmt * len(values), *values)
        view = {"buffer": 0, "byteOffset": offset, "byteLength": len(self.bin) - offset}
        if target:
            view["target"] = target
        self.views.append(view)
        acc = {"bufferView": len(self.views) - 1, "componentType": component_type, "count": count, "type": type_}
        if minmax:
            acc["min"], acc["max"] = minmax
        if normalized:
            acc["normalized"] = True
        self.accessors.append(acc)
        return len(self.accessors) - 1

    def doc(self, extra=None):
        positions = self.add("f", [0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0], 5126, "VEC3", 4, 34962,
                             ([0, 0, 0], [1, 1, 0]))
        normals = self.add("f", [0, 0, 1] * 4, 5126, "VEC3", 4, 34962)
        uvs = self.add("f", [0, 0, 1, 0, 0, 1, 1, 1], 5126, "VEC2", 4, 34962)
        joints = self.add("B", [0, 1, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0], 5121, "VEC4", 4, 34962)
        weights = self.add("f", [0.5, 0.5, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0.25, 0.75, 0, 0], 5126, "VEC4", 4, 34962)
        indices = self.add("H", [0, 1, 2, 2, 1, 3], 5123, "SCALAR", 6, 34963)
        ibm = self.add("f", [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,
                             1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1], 5126, "MAT4", 2)
        times = self.add("f", [0, 0.5, 1], 5126, "SCALAR", 3, None, ([0], [1]))
        rotations = self.add("f", [0, 0, 0, 1, 0, 0, 0.38268343, 0.9238795, 0, 0, 0.7071068, 0.7071068],
                             5126, "VEC4", 3)
        translations = self.add("f", [0, 1, 0, 0, 1.2, 0, 0, 1, 0], 5126, "VEC3", 3)
        scales = self.add("f", [0, 0, 0, 1, 1, 1, 0, 0, 0,
                                0, 0, 0, 1.5, 1.5, 1.5, 0, 0, 0,
                                0, 0, 0, 1, 1, 1, 0, 0, 0], 5126, "VEC3", 9)
        d = {
            "asset": {"version": "2.0", "generator": "tests/fuzz/make_corpus.py"},
            "scene": 0,
            "scenes": [{"nodes": [0, 1]}],
            "nodes": [
                {"name": "body", "mesh": 0, "skin": 0},
                {"name": "hip", "children": [2], "rotation": [0, 0, 0, 1]},
                {"name": "spine", "translation": [0, 1, 0], "scale": [1, 1, 1]},
            ],
            "meshes": [{"name": "quad", "primitives": [{
                "attributes": {"POSITION": positions, "NORMAL": normals, "TEXCOORD_0": uvs,
                               "JOINTS_0": joints, "WEIGHTS_0": weights},
                "indices": indices, "material": 0, "mode": 4}]}],
            "materials": [{"name": "skin", "pbrMetallicRoughness": {"baseColorFactor": [1, 0.8, 0.6, 1],
                                                                    "metallicFactor": 0, "roughnessFactor": 0.7},
                           "doubleSided": True}],
            "skins": [{"joints": [1, 2], "inverseBindMatrices": ibm, "skeleton": 1}],
            "animations": [{"name": "wave", "channels": [
                {"sampler": 0, "target": {"node": 2, "path": "rotation"}},
                {"sampler": 1, "target": {"node": 2, "path": "translation"}},
                {"sampler": 2, "target": {"node": 1, "path": "scale"}}],
                "samplers": [
                    {"input": times, "output": rotations, "interpolation": "LINEAR"},
                    {"input": times, "output": translations, "interpolation": "STEP"},
                    {"input": times, "output": scales, "interpolation": "CUBICSPLINE"}]}],
        }
        if extra:
            extra(self, d)
        d["bufferViews"] = self.views
        d["accessors"] = self.accessors
        d["buffers"] = [{"byteLength": len(self.bin)}]
        return d


def glb(doc, binary):
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    binary = bytes(binary) + b"\0" * (-len(binary) % 4)
    total = 12 + 8 + len(text) + 8 + len(binary)
    return (struct.pack("<III", 0x46546C67, 2, total) + struct.pack("<II", len(text), 0x4E4F534A) + text +
            struct.pack("<II", len(binary), 0x004E4942) + binary)


def embedded(doc, binary):
    doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(bytes(binary)).decode()
    return json.dumps(doc, indent=1)


def with_texture(model, d):
    image = png(2, 2, 6, 8, [bytes([255, 255, 255, 255, 0, 0, 0, 255])] * 2)
    while len(model.bin) % 4:
        model.bin.append(0)
    model.views.append({"buffer": 0, "byteOffset": len(model.bin), "byteLength": len(image)})
    model.bin += image
    d["images"] = [{"bufferView": len(model.views) - 1, "mimeType": "image/png"}]
    d["samplers"] = [{"magFilter": 9729, "minFilter": 9987}]
    d["textures"] = [{"source": 0, "sampler": 0}]
    d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}


def with_sparse_and_matrix(model, d):
    # Sparse translation keys over a zero base accessor, normalised u16 weights.
    idx = model.add("B", [1], 5121, "SCALAR", 1)
    vals = model.add("f", [0, 2, 0], 5126, "VEC3", 1)
    model.accessors.append({"componentType": 5126, "count": 3, "type": "VEC3", "sparse": {
        "count": 1, "indices": {"bufferView": model.accessors[idx]["bufferView"], "componentType": 5121},
        "values": {"bufferView": model.accessors[vals]["bufferView"]}}})
    d["animations"][0]["samplers"][1]["output"] = len(model.accessors) - 1
    w = model.add("H", [65535, 0, 0, 0] * 4, 5123, "VEC4", 4, 34962, normalized=True)
    d["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] = w
    d["nodes"][1] = {"name": "hip", "children": [2],
                     "matrix": [1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 0.5, 0, 1]}


def write_models():
    for target in ("gltf", "anim"):
        m = Model()
        d = m.doc()
        out(target, "skinned.glb", glb(d, m.bin))
        out(target, "skinned.gltf", embedded(d, m.bin))
        m = Model()
        d = m.doc(with_sparse_and_matrix)
        out(target, "sparse_matrix.gltf", embedded(d, m.bin))
    m = Model()
    d = m.doc(with_texture)
    out("gltf", "textured.glb", glb(d, m.bin))
    out("gltf", "empty.gltf", json.dumps({"asset": {"version": "2.0"}}))


if __name__ == "__main__":
    write_pngs()
    write_models()
