"""Reads one mesh's vertex positions out of a .glb, for the strand tests' byte-for-byte comparisons."""
import json
import struct


def mesh_positions(path, name):
    """The named mesh's POSITION bytes (first primitive), or None when the file has no such mesh."""
    b = open(path, "rb").read()
    n = struct.unpack("<I", b[12:16])[0]
    doc = json.loads(b[20:20 + n])
    binary = b[20 + n + 8:]
    for m in doc["meshes"]:
        if m["name"] == name:
            acc = doc["accessors"][m["primitives"][0]["attributes"]["POSITION"]]
            view = doc["bufferViews"][acc["bufferView"]]
            start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
            return binary[start:start + 12 * acc["count"]]
    return None
