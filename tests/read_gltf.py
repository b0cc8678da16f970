# SPDX-License-Identifier: GPL-3.0-or-later
"""Independent reader for origamic's glTF 2.0 files (.gltf with an embedded buffer, or .glb), by the
standard library alone: the GLB container, the data URI, accessors and buffer views as the glTF 2.0
specification lays them out.

usage: /usr/bin/python3 read_gltf.py FILE
prints JSON: {"version", "generator", "extras", "positions": [[x, y, z] in metres],
"min", "max" (the POSITION accessor's bounds), "triangles": [[i, j, k]], "triangle_material":
[index per triangle], "materials": [{"rgba", "double_sided", "metallic", "roughness"}]}."""
import base64
import json
import struct
import sys

COMPONENT = {5126: ("f", 4), 5125: ("I", 4), 5123: ("H", 2), 5121: ("B", 1)}
WIDTH = {"SCALAR": 1, "VEC3": 3}


def load(path):
    data = open(path, "rb").read()
    if data[:4] == b"glTF":
        magic, version, length = struct.unpack_from("<4sII", data, 0)
        assert version == 2 and length == len(data), "GLB header"
        offset, chunks = 12, []
        while offset < length:
            size, kind = struct.unpack_from("<I4s", data, offset)
            chunks.append((kind, data[offset + 8:offset + 8 + size]))
            offset += 8 + size
        assert chunks[0][0] == b"JSON", "GLB starts with its JSON chunk"
        doc = json.loads(chunks[0][1])
        binary = chunks[1][1] if len(chunks) > 1 and chunks[1][0] == b"BIN\x00" else b""
        buffers = [binary if "uri" not in b else None for b in doc.get("buffers", [])]
    else:
        doc = json.loads(data)
        buffers = []
        for b in doc.get("buffers", []):
            prefix, _, payload = b["uri"].partition(",")
            assert prefix.startswith("data:") and prefix.endswith(";base64"), "embedded buffer"
            buffers.append(base64.b64decode(payload))
    for b, raw in zip(doc.get("buffers", []), buffers):
        assert b["byteLength"] >= 1, "a buffer's byteLength is at least 1 (glTF 2.0 schema)"
        assert len(raw) >= b["byteLength"], "buffer shorter than its byteLength"
    return doc, buffers


def read_accessor(doc, buffers, index):
    accessor = doc["accessors"][index]
    view = doc["bufferViews"][accessor["bufferView"]]
    code, size = COMPONENT[accessor["componentType"]]
    width = WIDTH[accessor["type"]]
    start = view.get("byteOffset", 0) + accessor.get("byteOffset", 0)
    count = accessor["count"]
    assert start + count * width * size <= view.get("byteOffset", 0) + view["byteLength"], "accessor overruns its view"
    values = struct.unpack_from("<%d%s" % (count * width, code), buffers[view["buffer"]], start)
    return [list(values[i:i + width]) for i in range(0, len(values), width)], accessor


def main(path):
    doc, buffers = load(path)
    out = {"version": doc["asset"]["version"], "generator": doc["asset"].get("generator"),
           "extras": doc["asset"].get("extras"), "positions": [], "triangles": [], "triangle_material": [],
           "materials": []}
    for m in doc.get("materials", []):
        pbr = m.get("pbrMetallicRoughness", {})
        out["materials"].append({"rgba": pbr.get("baseColorFactor", [1, 1, 1, 1]),
                                 "double_sided": m.get("doubleSided", False),
                                 "metallic": pbr.get("metallicFactor", 1), "roughness": pbr.get("roughnessFactor", 1)})
    scene = doc["scenes"][doc.get("scene", 0)]
    position_accessor = None
    for node_index in scene["nodes"]:
        node = doc["nodes"][node_index]
        if "mesh" not in node:
            continue
        for primitive in doc["meshes"][node["mesh"]]["primitives"]:
            assert primitive.get("mode", 4) == 4, "triangles"
            if position_accessor is None:
                position_accessor = primitive["attributes"]["POSITION"]
                out["positions"], accessor = read_accessor(doc, buffers, position_accessor)
                out["min"], out["max"] = accessor["min"], accessor["max"]
            assert primitive["attributes"]["POSITION"] == position_accessor, "one shared vertex list"
            indices, _ = read_accessor(doc, buffers, primitive["indices"])
            flat = [i[0] for i in indices]
            for k in range(0, len(flat), 3):
                out["triangles"].append(flat[k:k + 3])
                out["triangle_material"].append(primitive["material"])
    json.dump(out, sys.stdout)


main(sys.argv[1])
