"""Hostile input files for tests/cli/run_hostile_tests.sh, written from first principles (no project code):
PNG headers with real CRCs, Ghost Tile caches forged the way an attacker would (payload rewritten, checksum
recomputed with an independent implementation of the documented hash), meshes with NaN and bad indices.

usage: hostile_inputs.py png OUT WIDTH HEIGHT            a valid tiny-IDAT PNG whose header claims WIDTHxHEIGHT
       hostile_inputs.py png-real OUT WIDTH HEIGHT       a real grayscale PNG of that size
       hostile_inputs.py forge-cache IN OUT WHAT          WHAT: tile_size | nan_position | zero_scale
"""
import struct
import sys
import zlib

M64 = (1 << 64) - 1


def png(path, width, height, rows=None):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    ihdr = struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)  # 8-bit grayscale
    raw = rows if rows is not None else b"\x00\x00"
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def png_real(path, width, height):
    rows = b"".join(b"\x00" + bytes((x * 7 + y * 3) % 256 for x in range(width)) for y in range(height))
    png(path, width, height, rows)


# The cache checksum (engine/core/hash.h documents it: four xxHash64-style lanes over 32-byte blocks, a
# SplitMix64 finalizer); re-implemented here the way a forger would.
def mix64(x):
    x = (x + 0x9E3779B97F4A7C15) & M64
    x = ((x ^ (x >> 30)) * 0xBF58476D1CE4E5B9) & M64
    x = ((x ^ (x >> 27)) * 0x94D049BB133111EB) & M64
    return x ^ (x >> 31)


def rotl(x, r):
    return ((x << r) | (x >> (64 - r))) & M64


def hash_bytes(data):
    p1, p2 = 0x9E3779B185EBCA87, 0xC2B2AE3D27D4EB4F
    state = [0x6A09E667F3BCC908, 0xBB67AE8584CAA73B, 0x3C6EF372FE94F82B, 0xA54FF53A5F1D36F1]
    full = len(data) // 32 * 32
    for off in range(0, full, 32):
        for lane in range(4):
            v = (state[lane] + struct.unpack_from("<Q", data, off + 8 * lane)[0] * p2) & M64
            state[lane] = (rotl(v, 31) * p1) & M64
    h = (rotl(state[0], 1) + rotl(state[1], 7) + rotl(state[2], 12) + rotl(state[3], 18)) & M64
    h = mix64(h ^ len(data))
    for i, b in enumerate(data[full:]):
        h = mix64(h ^ ((b << ((i % 8) * 8)) & M64) ^ i)
    return mix64(h)


HEADER = 8 + 4 + 4 + 8 + 8 + 8


def forge_cache(src, dst, what):
    data = bytearray(open(src, "rb").read())
    assert data[:8] == b"UGGHOST\0", "not a cache"
    assert hash_bytes(bytes(data[HEADER:])) == struct.unpack_from("<Q", data, 32)[0], "checksum re-implementation"
    payload = HEADER
    # Payload layout (ghost_tile_cache.cpp, format 2): f32 tile size, f32 delta, u64 seed, u32 variants, then
    # arrays (u64 count + items): type_begin u32, type u16, position vec3, rotation quat, scale f32, ...
    assert struct.unpack_from("<I", data, 8)[0] == 2, "cache format version"
    off = payload + 4 + 4 + 8 + 4
    arrays = {}
    for name, size in (("type_begin", 4), ("type", 2), ("position", 12), ("rotation", 16), ("scale", 4)):
        count = struct.unpack_from("<Q", data, off)[0]
        arrays[name] = off + 8
        off += 8 + count * size
    if what == "tile_size":
        struct.pack_into("<f", data, payload, struct.unpack_from("<f", data, payload)[0] * 2.0)
    elif what == "nan_position":
        struct.pack_into("<f", data, arrays["position"] + 12 * 5 + 4, float("nan"))
    elif what == "zero_scale":
        struct.pack_into("<f", data, arrays["scale"] + 4 * 9, 0.0)
    else:
        raise SystemExit("unknown forgery " + what)
    struct.pack_into("<Q", data, 32, hash_bytes(bytes(data[HEADER:])))
    open(dst, "wb").write(data)


if __name__ == "__main__":
    kind = sys.argv[1]
    if kind == "png":
        png(sys.argv[2], int(sys.argv[3]), int(sys.argv[4]))
    elif kind == "png-real":
        png_real(sys.argv[2], int(sys.argv[3]), int(sys.argv[4]))
    elif kind == "forge-cache":
        forge_cache(sys.argv[2], sys.argv[3], sys.argv[4])
    else:
        raise SystemExit(__doc__)
