#!/usr/bin/env python3
"""Writes the bad-input corpus into OUT_DIR: one broken model, image or scene per
case of tests/badinput (the table in README.md beside this file). Generated at
test time rather than committed, so that the large cases (a 4 GiB buffer, a
600 MiB file) cost nothing: they are sparse files.

Usage: make_bad_inputs.py OUT_DIR
"""
import json
import os
import struct
import sys
import zlib


class Model:
    """The valid base: a skinned, animated triangle; every case breaks one thing.
    Buffer layout (byte offsets): 0 positions 3 x vec3 | 36 joints 3 x u8vec4 |
    48 weights 3 x vec4 | 96 indices 3 x u16 (+2) | 104 inverse binds 2 x mat4 |
    232 key times 2 x f32 | 240 rotation keys 2 x vec4 (272 bytes)."""

    def __init__(self):
        b = bytearray(272)
        struct.pack_into("<9f", b, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0)
        struct.pack_into("<12B", b, 36, 0, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0)
        struct.pack_into("<12f", b, 48, 0.5, 0.5, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0)
        struct.pack_into("<3H", b, 96, 0, 1, 2)
        struct.pack_into("<32f", b, 104, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,
                         1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1)
        struct.pack_into("<2f", b, 232, 0.0, 1.0)
        struct.pack_into("<8f", b, 240, 0, 0, 0, 1, 0, 0, 0.7071068, 0.7071068)
        self.bin = b

        def view(offset, length):
            return {"buffer": 0, "byteOffset": offset, "byteLength": length}

        def acc(v, ct, count, type_):
            return {"bufferView": v, "componentType": ct, "count": count, "type": type_}

        self.doc = {
            "asset": {"version": "2.0"},
            "scene": 0,
            "scenes": [{"nodes": [0, 1]}],
            "nodes": [{"mesh": 0, "skin": 0, "name": "body"},
                      {"children": [2], "name": "hip"},
                      {"translation": [0, 1, 0], "name": "spine"}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "JOINTS_0": 1, "WEIGHTS_0": 2},
                                        "indices": 3}]}],
            "skins": [{"joints": [1, 2], "inverseBindMatrices": 4}],
            "animations": [{"channels": [{"sampler": 0, "target": {"node": 2, "path": "rotation"}}],
                            "samplers": [{"input": 5, "output": 6, "interpolation": "LINEAR"}]}],
            "buffers": [{"byteLength": 272}],
            "bufferViews": [view(0, 36), view(36, 12), view(48, 48), view(96, 6), view(104, 128),
                            view(232, 8), view(240, 32)],
            "accessors": [acc(0, 5126, 3, "VEC3"), acc(1, 5121, 3, "VEC4"), acc(2, 5126, 3, "VEC4"),
                          acc(3, 5123, 3, "SCALAR"), acc(4, 5126, 2, "MAT4"), acc(5, 5126, 2, "SCALAR"),
                          acc(6, 5126, 2, "VEC4")],
        }

    def glb(self):
        text = json.dumps(self.doc, separators=(",", ":")).encode()
        text += b" " * (-len(text) % 4)
        total = 12 + 8 + len(text) + 8 + len(self.bin)
        return (struct.pack("<III", 0x46546C67, 2, total) + struct.pack("<II", len(text), 0x4E4F534A) + text +
                struct.pack("<II", len(self.bin), 0x004E4942) + bytes(self.bin))


def png(width, height, rows=None):
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    raw = b"".join(b"\x00" + r for r in (rows or []))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def pfm(width, height, pixels):
    """A colour PFM, little-endian (scale -1), rows bottom to top; `pixels` RGB
    triples top row first."""
    rows = [pixels[y * width:(y + 1) * width] for y in range(height)]
    data = b"".join(struct.pack("<%df" % (3 * width), *[c for p in row for c in p]) for row in reversed(rows))
    return b"PF\n%d %d\n-1.0\n" % (width, height) + data


def exr(width, height, pixels):
    """An uncompressed scanline OpenEXR of float B, G, R channels, written from the
    specification rather than by tinyexr (the reader must take files it did not
    write); `pixels` RGB triples top row first."""
    def attr(name, kind, data):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(data)) + data
    channels = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for c in "BGR") + b"\0"
    box = struct.pack("<iiii", 0, 0, width - 1, height - 1)
    header = (b"\x76\x2f\x31\x01" + struct.pack("<I", 2) + attr("channels", "chlist", channels) +
              attr("compression", "compression", b"\0") + attr("dataWindow", "box2i", box) +
              attr("displayWindow", "box2i", box) + attr("lineOrder", "lineOrder", b"\0") +
              attr("pixelAspectRatio", "float", struct.pack("<f", 1)) +
              attr("screenWindowCenter", "v2f", struct.pack("<ff", 0, 0)) +
              attr("screenWindowWidth", "float", struct.pack("<f", 1)) + b"\0")
    lines, offsets = [], []
    at = len(header) + 8 * height
    for y in range(height):
        row = pixels[y * width:(y + 1) * width]
        data = b"".join(struct.pack("<%df" % width, *[p[k] for p in row]) for k in (2, 1, 0))
        offsets.append(at)
        lines.append(struct.pack("<ii", y, len(data)) + data)
        at += len(lines[-1])
    return header + struct.pack("<%dQ" % height, *offsets) + b"".join(lines)


def main(out):
    os.makedirs(out, exist_ok=True)

    def write(name, data):
        with open(os.path.join(out, name), "wb") as f:
            f.write(data if isinstance(data, bytes) else data.encode())

    def case(name, edit=None, binary=True):
        m = Model()
        if edit:
            edit(m)
        if binary:
            write(name, m.glb())
        else:
            m.doc["buffers"][0].setdefault("uri", name.rsplit(".", 1)[0] + ".bin")
            uri = m.doc["buffers"][0]["uri"]
            if "/" not in uri and not os.path.exists(os.path.join(out, uri)):
                write(uri, bytes(m.bin))
            write(name, json.dumps(m.doc))

    case("good.glb")
    write("truncated.glb", Model().glb()[:30])
    write("wrong_magic.glb", b"glTX" + Model().glb()[4:])
    # JSON chunk length past the end of the file (header length left consistent).
    g = bytearray(Model().glb())
    struct.pack_into("<I", g, 12, len(g))
    write("json_chunk_past_end.glb", bytes(g))
    # BIN chunk length past the end.
    g = bytearray(Model().glb())
    json_len = struct.unpack_from("<I", g, 12)[0]
    struct.pack_into("<I", g, 20 + json_len, 1 << 20)
    write("bin_chunk_past_end.glb", bytes(g))

    def set_(path, value):
        def edit(m):
            node = m.doc
            for key in path[:-1]:
                node = node[key]
            node[path[-1]] = value
        return edit

    # 2^32 - 1 elements: must be refused from the count alone, before any allocation.
    case("accessor_count_overflow.glb", set_(["accessors", 0, "count"], 4294967295))
    # One past kMaxAccessorElements (2^26).
    case("accessor_count_limit.glb", set_(["accessors", 5, "count"], (1 << 26) + 1))
    case("bufferview_past_buffer.glb", set_(["bufferViews", 6, "byteLength"], 64))

    def joint_past_skin(m):
        m.bin[36 + 4] = 5  # vertex 1 names joint 5 of a 2-joint skin
    case("joint_past_skin.glb", joint_past_skin)

    def morph_target_count(m):
        # A target of 2 displacements on a 3-vertex primitive.
        m.doc["accessors"].append({"bufferView": 0, "componentType": 5126, "count": 2, "type": "VEC3"})
        m.doc["meshes"][0]["primitives"][0]["targets"] = [{"POSITION": 7}]
    case("morph_target_count.glb", morph_target_count)

    def morph_weights_keys(m):
        # One target, two keys: the weights output needs 2 values, it has 3.
        m.doc["meshes"][0]["primitives"][0]["targets"] = [{"POSITION": 0}]
        m.doc["accessors"].append({"bufferView": 6, "componentType": 5126, "count": 3, "type": "SCALAR"})
        m.doc["animations"][0]["samplers"].append({"input": 5, "output": 7})
        m.doc["animations"][0]["channels"].append({"sampler": 1, "target": {"node": 0, "path": "weights"}})
    case("morph_weights_keys.glb", morph_weights_keys)

    def key_time(value, index=1):
        def edit(m):
            struct.pack_into("<f", m.bin, 232 + 4 * index, value)
        return edit
    case("negative_key_time.glb", key_time(-1.0, 0))
    case("nan_key_time.glb", key_time(float("nan")))

    def unsorted(m):
        struct.pack_into("<2f", m.bin, 232, 1.0, 0.5)
    case("unsorted_keys.glb", unsorted)

    def cycle(m):
        m.doc["nodes"][2]["children"] = [1]  # hip -> spine -> hip
    case("node_cycle.glb", cycle)
    case("uri_dotdot.gltf", set_(["buffers", 0, "uri"], "../outside.bin"), binary=False)
    case("uri_absolute.gltf", set_(["buffers", 0, "uri"], "/etc/passwd"), binary=False)

    # A buffer declaring 4 GiB: first with a small file behind it, then with a real
    # (sparse) 4 GiB file, which the file-size limit must refuse before reading.
    def declared_4gb(uri):
        def edit(m):
            m.doc["buffers"][0] = {"byteLength": 1 << 32, "uri": uri}
        return edit
    case("buffer_4gb_declared.gltf", declared_4gb("small.bin"), binary=False)
    write("small.bin", bytes(Model().bin))
    case("buffer_4gb_file.gltf", declared_4gb("huge.bin"), binary=False)
    with open(os.path.join(out, "huge.bin"), "wb") as f:
        f.truncate(1 << 32)

    # A model file over kMaxModelFileBytes (512 MiB): a GLB padded with a sparse tail.
    with open(os.path.join(out, "file_too_large.glb"), "wb") as f:
        f.write(Model().glb())
        f.truncate(600 << 20)

    # kMaxSkinJoints + 1 joints (65537 nodes under one root).
    def many_joints(m):
        n = (1 << 16) + 1
        m.doc["nodes"] = [{"mesh": 0, "skin": 0}, {"children": list(range(2, n + 1))}] + [{}] * (n - 1)
        m.doc["scenes"] = [{"nodes": [0, 1]}]
        m.doc["skins"] = [{"joints": list(range(1, n + 1))}]
        m.doc["animations"] = []
    case("too_many_joints.glb", many_joints)

    # kMaxNodes + 1 nodes (2^20 + 1 empty nodes, 3 MiB of JSON).
    write("too_many_nodes.gltf", json.dumps({"asset": {"version": "2.0"}, "nodes": [{}] * ((1 << 20) + 1)},
                                            separators=(",", ":")))

    # Images: a 0x0 PNG and one claiming 20000 x 20000 pixels, on their own (for
    # imgdiff) and embedded as a model's texture (the loader warns and falls back).
    write("zero_size.png", png(0, 0))
    write("huge_claim.png", png(20000, 20000))

    # imgdiff's masks (--mask): one of the wrong size and one that selects nothing,
    # for a 4x4 pair; and a second image of another size.
    write("mask_pair.png", png(4, 4, [b"\x80\x40\x20\xff" * 4] * 4))
    write("mask_small.png", png(2, 2, [b"\xff" * 8] * 2))
    write("mask_black.png", png(4, 4, [b"\x00\x00\x00\xff" * 4] * 4))
    write("other_size.png", png(4, 3, [b"\x80\x40\x20\xff" * 4] * 3))

    # Float images for imgdiff: the same 4x4 pixels (up to 1e30) as OpenEXR and as
    # PFM, which must read alike; each cut short, a PFM with bytes to spare, a file
    # named .exr that is text.
    light = [(0.5 * x, 2.0 ** y, 1e30 if x == y else 0.0) for y in range(4) for x in range(4)]
    good_exr, good_pfm = exr(4, 4, light), pfm(4, 4, light)
    write("good.exr", good_exr)
    write("good.pfm", good_pfm)
    write("truncated.exr", good_exr[:len(good_exr) - 20])
    write("truncated.pfm", good_pfm[:len(good_pfm) - 4 * 4 * 12 + 100])  # 100 bytes of 192
    write("wrong_size.pfm", good_pfm + b"\0" * 8)
    write("not_an_image.exr", "this is not an image\n")

    def with_image(data):
        def edit(m):
            off = len(m.bin)
            m.bin += data + b"\0" * (-len(data) % 4)
            m.doc["buffers"][0]["byteLength"] = len(m.bin)
            m.doc["bufferViews"].append({"buffer": 0, "byteOffset": off, "byteLength": len(data)})
            m.doc["images"] = [{"bufferView": 7, "mimeType": "image/png"}]
            m.doc["textures"] = [{"source": 0}]
            m.doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
            m.doc["meshes"][0]["primitives"][0]["material"] = 0
        return edit
    case("zero_size_image.glb", with_image(png(0, 0)))
    case("huge_image.glb", with_image(png(20000, 20000)))

    # Texture settings the engine cannot honour: a uv set past TEXCOORD_1, a
    # malformed KHR_texture_transform, a wrap mode that is not one.
    def bad_texture_settings(m):
        with_image(png(2, 2, [b"\xff" * 8] * 2))(m)
        m.doc["extensionsUsed"] = ["KHR_texture_transform"]
        m.doc["samplers"] = [{"wrapS": 1, "minFilter": 7}]
        m.doc["textures"][0]["sampler"] = 0
        m.doc["materials"][0]["name"] = "tiles"
        m.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {
            "index": 0, "texCoord": 2, "extensions": {"KHR_texture_transform": {"offset": "far", "scale": [1]}}}
    case("bad_texture_settings.glb", bad_texture_settings)

    # KHR_materials_clearcoat with a coat weight past 1 (the ior and specular keys
    # go through the same check).
    def bad_clearcoat(m):
        m.doc["extensionsUsed"] = ["KHR_materials_clearcoat"]
        m.doc["materials"] = [{"name": "paint", "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 2.5}}}]
        m.doc["meshes"][0]["primitives"][0]["material"] = 0
    case("bad_clearcoat.glb", bad_clearcoat)

    # KHR_materials_volume with an attenuation colour past 1 (a medium that would
    # add light); the other volume and transmission keys go through the same checks.
    def bad_volume(m):
        m.doc["extensionsUsed"] = ["KHR_materials_transmission", "KHR_materials_volume"]
        m.doc["materials"] = [{"name": "glass", "extensions": {
            "KHR_materials_transmission": {"transmissionFactor": 1.0},
            "KHR_materials_volume": {"thicknessFactor": 0.1, "attenuationColor": [1.0, 1.5, 1.0]}}}]
        m.doc["meshes"][0]["primitives"][0]["material"] = 0
    case("bad_volume.glb", bad_volume)

    # KHR_materials_sheen with a roughness past 1; its colour goes through the same
    # range check as the other extensions' colours.
    def bad_sheen(m):
        m.doc["extensionsUsed"] = ["KHR_materials_sheen"]
        m.doc["materials"] = [{"name": "velvet", "extensions": {
            "KHR_materials_sheen": {"sheenColorFactor": [0.5, 0.5, 0.5], "sheenRoughnessFactor": 1.5}}}]
        m.doc["meshes"][0]["primitives"][0]["material"] = 0
    case("bad_sheen.glb", bad_sheen)

    # KHR_materials_anisotropy with a strength past 1.
    def bad_anisotropy(m):
        m.doc["extensionsUsed"] = ["KHR_materials_anisotropy"]
        m.doc["materials"] = [{"name": "brushed", "extensions": {
            "KHR_materials_anisotropy": {"anisotropyStrength": 2.0}}}]
        m.doc["meshes"][0]["primitives"][0]["material"] = 0
    case("bad_anisotropy.glb", bad_anisotropy)

    # KHR_materials_iridescence with a film index below 1.
    def bad_iridescence(m):
        m.doc["extensionsUsed"] = ["KHR_materials_iridescence"]
        m.doc["materials"] = [{"name": "soap", "extensions": {
            "KHR_materials_iridescence": {"iridescenceFactor": 1.0, "iridescenceIor": 0.5}}}]
        m.doc["meshes"][0]["primitives"][0]["material"] = 0
    case("bad_iridescence.glb", bad_iridescence)

    # KHR_lights_punctual: a spot whose inner cone is wider than its outer one.
    def bad_spot_cone(m):
        m.doc["extensionsUsed"] = ["KHR_lights_punctual"]
        m.doc["extensions"] = {"KHR_lights_punctual": {"lights": [
            {"type": "spot", "name": "torch", "spot": {"innerConeAngle": 0.8, "outerConeAngle": 0.4}}]}}
        m.doc["nodes"][0].setdefault("extensions", {})["KHR_lights_punctual"] = {"light": 0}
    case("bad_spot_cone.glb", bad_spot_cone)

    # Compressed geometry cut short. Draco: a stream with a whole header (magic,
    # version 2.2, a triangle mesh, edgebreaker) and nothing after it. Meshopt: the
    # positions as a vertex stream of 3 x 12 bytes whose data stops after the
    # header byte and a few more.
    def compressed(ext):
        def edit(m):
            off = len(m.bin)
            data = {"KHR_draco_mesh_compression": b"DRACO\x02\x02\x01\x01\x00\x00",
                    "EXT_meshopt_compression": b"\xa0\x00\x00\x00\x00\x00"}[ext]
            m.bin += data + b"\0" * (-len(data) % 4)
            m.doc["buffers"][0]["byteLength"] = len(m.bin)
            m.doc["extensionsUsed"] = m.doc["extensionsRequired"] = [ext]
            if ext == "KHR_draco_mesh_compression":
                m.doc["bufferViews"].append({"buffer": 0, "byteOffset": off, "byteLength": len(data)})
                m.doc["meshes"][0]["primitives"][0]["extensions"] = {ext: {"bufferView": 7, "attributes": {"POSITION": 0}}}
            else:
                m.doc["bufferViews"][0]["extensions"] = {ext: {"buffer": 0, "byteOffset": off, "byteLength": len(data),
                                                               "byteStride": 12, "count": 3, "mode": "ATTRIBUTES"}}
        return edit
    case("draco_truncated.glb", compressed("KHR_draco_mesh_compression"))
    case("meshopt_truncated.glb", compressed("EXT_meshopt_compression"))

    # EXT_mesh_gpu_instancing on node 0 with attributes that do not fit: ROTATION
    # naming the VEC3 positions (wrong type), and a ROTATION of 2 instances beside
    # a TRANSLATION of 3 (counts differ).
    def instancing(attributes):
        def edit(m):
            m.doc["extensionsUsed"] = ["EXT_mesh_gpu_instancing"]
            m.doc["nodes"][0]["extensions"] = {"EXT_mesh_gpu_instancing": {"attributes": attributes}}
        return edit
    case("instancing_type.glb", instancing({"TRANSLATION": 0, "ROTATION": 0}))
    case("instancing_count.glb", instancing({"TRANSLATION": 0, "ROTATION": 6}))

    # One instance past kMaxNodeInstances (2^20): a sparse TRANSLATION accessor of
    # zeros with one vec3 replaced, a few bytes in the file.
    def too_many_instances(m):
        instancing({"TRANSLATION": 7})(m)
        m.doc["accessors"].append({"componentType": 5126, "count": (1 << 20) + 1, "type": "VEC3",
                                   "sparse": {"count": 1, "indices": {"bufferView": 3, "componentType": 5123},
                                              "values": {"bufferView": 0}}})
    case("instancing_too_many.glb", too_many_instances)

    # Scene files (the format of assets/scenes/*.json) with values of the wrong type.
    write("scene_fovy_string.json", json.dumps({"camera": {"fovy": "wide"}}))
    write("scene_models_number.json", json.dumps({"models": 5}))
    write("scene_model_path_number.json", json.dumps({"models": [{"path": 3}]}))
    write("scene_light_type.json", json.dumps({"lights": [{"type": 7}]}))
    write("scene_spot_cone_inverted.json", json.dumps({"lights": [
        {"type": "spot", "position": [0, 3, 0], "inner_cone": 40, "outer_cone": 30}]}))
    write("scene_fog_negative_scattering.json", json.dumps({"fog": {"model": "volumetric", "scattering": [0.1, -1, 0.1]}}))
    write("scene_fog_anisotropy_one.json", json.dumps({"fog": {"model": "volumetric", "anisotropy": 1.0}}))
    write("scene_fog_height_falloff_negative.json", json.dumps({"fog": {"model": "volumetric", "height_falloff": -0.01}}))
    write("scene_atmosphere_radius_zero.json", json.dumps({"atmosphere": {"planet_radius": 0}}))
    write("scene_atmosphere_mie_infinite.json", '{"atmosphere": {"mie": {"scattering": [1e-6, 1e999, 1e-6]}}}')
    write("scene_atmosphere_mie_anisotropy_one.json", json.dumps({"atmosphere": {"mie": {"anisotropy": 1.0}}}))
    write("scene_medium_box_inverted.json", json.dumps({"media": [
        {"type": "box", "min": [0, 0, 0], "max": [1, -1, 1], "scattering": [0.1, 0.1, 0.1]}]}))
    write("scene_medium_negative_absorption.json", json.dumps({"media": [
        {"type": "box", "min": [0, 0, 0], "max": [1, 1, 1], "absorption": [0.1, 0.1, -0.1]}]}))
    write("scene_point_cone.json", json.dumps({"lights": [{"type": "point", "outer_cone": 30}]}))
    write("scene_position_null.json", json.dumps({"camera": {"position": [1, None, 3]}}))
    write("scene_msaa_string.json", json.dumps({"render": {"msaa": "four"}}))
    write("scene_skinning_unknown.json", json.dumps({"render": {"skinning": "gpu"}}))
    write("scene_lod_negative.json", json.dumps({"render": {"lod_pixels": -1}}))
    write("scene_gpu_culling_string.json", json.dumps({"render": {"gpu_culling": "on"}}))
    write("scene_unknown_key.json", json.dumps({"origin": [0, 0, 0]}))
    write("scene_not_object.json", json.dumps([1, 2, 3]))

    # Sky images: missing, not an image (by content: the name says .hdr), an empty
    # file, a Radiance header of 0 x 0 pixels, the 0x0 PNG above, and a run-length
    # .hdr cut short (its header is fine; the decoder must refuse it, not hang).
    def sky_scene(name, image):
        write(name, json.dumps({"sky": {"image": image}}))
    sky_scene("scene_sky_image_missing.json", "no_such_sky.hdr")
    write("not_an_image.hdr", b"this is text, not a Radiance image\n")
    sky_scene("scene_sky_image_not_image.json", "not_an_image.hdr")
    write("empty.hdr", b"")
    sky_scene("scene_sky_image_empty.json", "empty.hdr")
    write("zero_size.hdr", b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 0 +X 0\n")
    sky_scene("scene_sky_image_zero_size.json", "zero_size.hdr")
    sky_scene("scene_sky_image_zero_png.json", "zero_size.png")
    # 16 x 4 pixels, each scanline a mark and per channel one literal run of 16 bytes;
    # cut after a scanline and a half.
    scanline = bytes([2, 2, 0, 16]) + (bytes([16]) + bytes([100] * 16)) * 3 + bytes([16]) + bytes([129] * 16)
    whole = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 16\n" + scanline * 4
    write("truncated_sky.hdr", whole[:-len(scanline) * 2 - len(scanline) // 2])
    sky_scene("scene_sky_image_truncated.json", "truncated_sky.hdr")

if __name__ == "__main__":
    main(sys.argv[1])
