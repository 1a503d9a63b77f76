"""The environment meshes of a GLB export (env/, snow/, icicles/), each hashed from the file's own bytes:
its vertices, its triangles and every placement (node translation, instancing translations). Two exports
with equal dictionaries hold the same environmental objects and effects.

    python3 env_meshes.py A.glb B.glb   exits 0 when both hold the same, 1 (with the differences) otherwise
"""
import hashlib
import json
import struct
import sys


def env_meshes(path):
    b = open(path, "rb").read()
    n = struct.unpack("<I", b[12:16])[0]
    doc = json.loads(b[20:20 + n])
    binary = b[20 + n + 8:]

    def data(i):
        a = doc["accessors"][i]
        v = doc["bufferViews"][a["bufferView"]]
        start = v.get("byteOffset", 0) + a.get("byteOffset", 0)
        return binary[start:start + v["byteLength"] - a.get("byteOffset", 0)]

    out = {}
    for m, mesh in enumerate(doc["meshes"]):
        if mesh["name"].split("/")[0] not in ("env", "snow", "icicles"):
            continue
        h = hashlib.sha1()
        for p in mesh["primitives"]:
            h.update(data(p["attributes"]["POSITION"]))
            h.update(data(p["indices"]))
        for node in doc["nodes"]:
            if node.get("mesh") == m:
                inst = node.get("extensions", {}).get("EXT_mesh_gpu_instancing", {}).get("attributes", {})
                h.update(json.dumps(node.get("translation")).encode())
                if "TRANSLATION" in inst:
                    h.update(data(inst["TRANSLATION"]))
        out[mesh["name"]] = h.hexdigest()
    return out


def triangles(path, prefix):
    """Triangles of the meshes whose name starts with `prefix`, times their placements."""
    b = open(path, "rb").read()
    n = struct.unpack("<I", b[12:16])[0]
    doc = json.loads(b[20:20 + n])
    total = 0
    for m, mesh in enumerate(doc["meshes"]):
        if not mesh["name"].startswith(prefix):
            continue
        tris = sum(doc["accessors"][p["indices"]]["count"] // 3 for p in mesh["primitives"])
        for node in doc["nodes"]:
            if node.get("mesh") == m:
                inst = node.get("extensions", {}).get("EXT_mesh_gpu_instancing", {}).get("attributes", {})
                total += tris * (doc["accessors"][inst["TRANSLATION"]]["count"] if "TRANSLATION" in inst else 1)
    return total


if __name__ == "__main__":
    a, b = env_meshes(sys.argv[1]), env_meshes(sys.argv[2])
    if a != b or not a:
        print("differ:", sorted(set(a.items()) ^ set(b.items()))[:6])
        sys.exit(1)
    print("%d environment meshes equal" % len(a))
