#!/usr/bin/env python3
"""Writes the seeds of the fuzz targets' corpora (fuzz/corpus/TARGET/) from the repository's data
and small files built here (uncompressed OpenEXR, 16-bit PNG, a one-triangle GLB and glTF).
Run from anywhere: python3 fuzz/make_seeds.py. Standard library only."""
import base64, json, struct, zlib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CORPUS = ROOT / "fuzz" / "corpus"


def exr(width, height, channels):
    """Uncompressed scanline OpenEXR; channels: {name: [float] * width*height}."""
    def attr(name, kind, value):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value
    names = sorted(channels)
    chlist = b"".join(n.encode() + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for n in names) + b"\0"
    box = struct.pack("<4i", 0, 0, width - 1, height - 1)
    header = (b"\x76\x2f\x31\x01" + struct.pack("<I", 2)
              + attr("channels", "chlist", chlist) + attr("compression", "compression", b"\0")
              + attr("dataWindow", "box2i", box) + attr("displayWindow", "box2i", box)
              + attr("lineOrder", "lineOrder", b"\0") + attr("pixelAspectRatio", "float", struct.pack("<f", 1))
              + attr("screenWindowCenter", "v2f", struct.pack("<2f", 0, 0))
              + attr("screenWindowWidth", "float", struct.pack("<f", 1)) + b"\0")
    blocks = []
    for y in range(height):
        data = b"".join(struct.pack(f"<{width}f", *channels[n][y * width:(y + 1) * width]) for n in names)
        blocks.append(struct.pack("<ii", y, len(data)) + data)
    offset = len(header) + 8 * height
    table = b""
    for b in blocks:
        table += struct.pack("<Q", offset)
        offset += len(b)
    return header + table + b"".join(blocks)


def png16(width, height, values):
    """16-bit greyscale PNG."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    raw = b"".join(b"\0" + struct.pack(f">{width}H", *values[y * width:(y + 1) * width]) for y in range(height))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 16, 0, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def triangle_gltf():
    """(json dict, binary buffer) of one textured triangle with u16 indices."""
    pos = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    uv = struct.pack("<6f", 0, 0, 1, 0, 0, 1)
    idx = struct.pack("<3H", 0, 1, 2) + b"\0\0"
    buf = pos + uv + idx
    doc = {
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": "face"}],
        "meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2}]}],
        "buffers": [{"byteLength": len(buf)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                        {"buffer": 0, "byteOffset": 36, "byteLength": 24},
                        {"buffer": 0, "byteOffset": 60, "byteLength": 6}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"},
                      {"bufferView": 2, "componentType": 5123, "count": 3, "type": "SCALAR"}],
    }
    return doc, buf


def glb(doc, buf):
    js = json.dumps(doc).encode()
    js += b" " * (-len(js) % 4)
    buf += b"\0" * (-len(buf) % 4)
    body = struct.pack("<I4s", len(js), b"JSON") + js + struct.pack("<I4s", len(buf), b"BIN\0") + buf
    return struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body


def project_input(files):
    """fuzz/src/lib.rs split_project's layout: name index, u16 length, contents."""
    names = ["look.json", "face.json", "skin.json", "maps/layer.exr", "maps/layer.png", "presets/p.json",
             "maps/skin.exr", "maps/edits.exr"]
    return b"".join(bytes([names.index(n)]) + struct.pack("<H", len(c)) + c for n, c in files)


def main():
    # Writes (or rewrites) the seeds only: the files the fuzz runs added stay.
    def put(target, name, data):
        d = CORPUS / target
        d.mkdir(parents=True, exist_ok=True)
        (d / name).write_bytes(data if isinstance(data, bytes) else data.encode())
    def copy(target, paths):
        for p in paths:
            put(target, p.name, p.read_bytes())

    data = ROOT / "data"
    copy("measurement", sorted((data / "measurements").glob("*_0[12]_*.csv"))[:4])
    copy("measurement", [p for p in sorted((data / "measurements" / "formats").iterdir()) if p.stat().st_size < 40000])
    copy("preset", sorted((data / "presets").glob("*.json"))[:6] + sorted((data / "finishes").glob("*.json"))[:2])
    copy("look", sorted((data / "looks").glob("*.json")))
    copy("medium", sorted((data / "media").glob("*.json")))

    face = {"format": "rouge-face", "version": 1, "expression": {"smile": 0.6}, "shape": {"nose-hump": 0.3}}
    put("face", "smile.json", json.dumps(face, indent=1))
    put("face", "neutral.json", '{"format": "rouge-face", "version": 1}')

    n = 4 * 4
    skin_ch = {"melanin_fraction": 0.05, "pheomelanin_share": 0.3, "blood_fraction": 0.02,
               "oxygen_saturation": 0.75, "epidermis_thickness_mm": 0.08}
    skin = exr(4, 4, {k: [v] * n for k, v in skin_ch.items()})
    edits = exr(4, 4, {"melanin_ln_factor": [0.1] * n, "blood_ln_factor": [-0.1] * n})
    put("skin_exr", "maps.exr", skin)
    put("skin_exr", "edits.exr", edits)

    obj = ("# a textured quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
           "vn 0 0 1\ng quad\nusemtl skin\nf 1/1/1 2/2/1 3/3/1 4/4/1\nf -4/-4 -2/-2 -1/-1\n")
    put("obj", "quad.obj", obj)

    doc, buf = triangle_gltf()
    put("gltf", "triangle.glb", glb(doc, buf))
    doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(buf).decode()
    put("gltf", "triangle.gltf", json.dumps(doc))

    layer = exr(8, 8, {"Y": [0.001 * (i % 8) for i in range(64)]})
    put("map", "layer.exr", layer)
    # An environment map: radiance in R, G, B (and an alpha the reader ignores).
    put("env", "studio.exr", exr(8, 4, {"R": [0.5 + 0.1 * i for i in range(32)], "G": [0.4] * 32,
                                        "B": [0.3] * 32, "A": [1.0] * 32}))
    put("map", "layer.png", png16(8, 8, [i * 1000 for i in range(64)]))

    look = {"schema": "rouge-look", "version": 1, "name": "Fuzz", "layers": [
        {"preset": "builtin:foundation_02_ivory", "thickness": {"map": "maps/layer.exr", "scale_mm": 1.0}},
        {"preset": "presets/p.json", "thickness": {"map": "maps/layer.png", "scale_mm": 0.02}},
        {"preset": "builtin:lipstick_02_red", "thickness": {"region": "lips", "thickness_mm": 0.02}}]}
    base = {"melanin_fraction": 0.05, "pheomelanin_share": 0.3, "blood_fraction": 0.02, "oxygen_saturation": 0.75,
            "scattering_500nm_per_mm": 2.0, "scattering_power": 1.5, "epidermis_thickness_mm": 0.08}
    skin_json = {"format": "rouge-skin", "version": 1, "maps": "maps/skin.exr", "edits": "maps/edits.exr",
                 "recipe": {"base": base, "seed": 1, "size_px": 4}}
    preset = (data / "presets" / "blush_01_petal.json").read_bytes()
    put("project", "full", project_input([
        ("look.json", json.dumps(look).encode()), ("face.json", json.dumps(face).encode()),
        ("skin.json", json.dumps(skin_json).encode()), ("maps/layer.exr", layer),
        ("maps/layer.png", png16(8, 8, [i * 1000 for i in range(64)])), ("presets/p.json", preset),
        ("maps/skin.exr", skin), ("maps/edits.exr", edits)]))
    put("project", "minimal", project_input([("look.json", json.dumps({"schema": "rouge-look", "version": 1,
        "layers": [{"preset": "builtin:blush_01_petal", "thickness": {"uniform_mm": 0.01}}]}).encode())]))


if __name__ == "__main__":
    main()
