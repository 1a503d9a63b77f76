// Bounded readers for the classic model formats (OBJ, PLY, STL, OFF), and the limits every model
// reader (these and glTF) enforces.
//
// Model files come from users and the web, so each reader is written for hostile input: it never
// loops without consuming input, checks every count a file declares against the bytes that are
// actually there and against the limits below BEFORE allocating, and turns NaN/Inf coordinates, bad
// indices, degenerate faces and truncation into an error that names the file and the element. A
// reader prints nothing; the returned error string is the only report.
//
//   std::vector<unsigned char> bytes;
//   std::string error;
//   if (!readMeshFileBytes(path, &bytes, &error)) return report(error);
//   TriangleMesh mesh;
//   if (!readObj(asText(bytes), path, &mesh, &error)) return report(error);
//
// Most callers want loadMeshFile (mesh/mesh_loader.h), which picks the reader by extension. The
// readers take the file's bytes, not a path, so a fuzz harness can call them on memory.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "mesh/triangle_mesh.h"

namespace ug {

// ---- Limits ----------------------------------------------------------------------------------------
// A detail model is scattered thousands of times; anything near these sizes is a mistake or an attack,
// and refusing it early keeps memory within a small multiple of the file's own size.
inline constexpr uint64_t kMaxMeshFileBytes = uint64_t(2) << 30;  // 2 GiB; glTF: file + external files
inline constexpr uint64_t kMaxMeshVertices = 50'000'000;          // per model (STL: after welding)
inline constexpr uint64_t kMaxMeshTriangles = 50'000'000;         // per model, after triangulation
inline constexpr size_t kMaxPlyHeaderBytes = 64 * 1024;           // "end_header" must end within this

// Reads a whole model file. Refuses a file larger than kMaxMeshFileBytes before reading any of it.
// False with "<path>: <reason>" (missing, not a regular file, too large, read error).
bool readMeshFileBytes(const std::string& path, std::vector<unsigned char>* bytes, std::string* error);

inline std::string_view asText(const std::vector<unsigned char>& bytes) {
    return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
}

// ---- Readers ---------------------------------------------------------------------------------------
// Common contract: `bytes` is the whole file, `name` prefixes every error ("<name>: <reason>", usually
// the path). On success `out` gets positions and indices in the file's own axes and units (no
// conversion), normals recomputed (computeNormals) and the default base_color, and passes
// validateMesh; on failure `out` is untouched. Polygons are fan-triangulated (v0, vi, vi+1), keeping
// the file's winding. Every error names the element: OBJ numbers vertices and faces from 1 (as its
// indices do) and adds the line; PLY, OFF and STL number from 0 (PLY/OFF indices are 0-based) and add
// the line for text encodings. Time and memory are linear in the file's size.

// Wavefront OBJ. Reads `v x y z [w ...]` (extra values such as w or colours ignored) and
// `f` with corners `v`, `v/vt`, `v/vt/vn` or `v//vn`; negative indices count back from the latest
// vertex (-1 = the vertex just before the face), positive ones from the start of the file (a face may
// refer to a vertex defined later). Every other statement (vt, vn, o, g, s, usemtl, mtllib, l, p,
// curves) is ignored; '#' starts a comment; a trailing '\' continues a line; "\r\n" is fine.
// Errors: index 0, an index beyond the file's vertices or before its first, a face with fewer than 3
// corners, a vertex with fewer than 3 numbers, a non-number, a non-finite coordinate (also a finite
// double beyond float range), no faces.
bool readObj(std::string_view bytes, const std::string& name, TriangleMesh* out, std::string* error);

// Stanford PLY 1.0: ascii, binary_little_endian or binary_big_endian. The header starts with "ply" and
// must reach "end_header" within kMaxPlyHeaderBytes. Needs an element "vertex" with scalar properties
// x, y, z (any PLY scalar type: char/int8 ... double/float64) and an element "face" with a list
// property "vertex_indices" or "vertex_index" (any integer count and index types). Other properties of
// these two (normals, colours, texture lists) and other elements (edges, materials, ...) are skipped.
// Every element's count is checked against the bytes after the header and against the limits before
// anything is allocated. Errors also cover negative or out-of-range indices, faces with fewer than 3
// corners and truncation ("truncated in the face list at face 5 of 12"). Bytes after the last element
// are ignored.
bool readPly(std::string_view bytes, const std::string& name, TriangleMesh* out, std::string* error);

// STL, binary or ASCII. Binary: an 80-byte header, a little-endian u32 triangle count, then 50 bytes per
// triangle (normal, three corners, attribute); the file must hold at least 84 + 50 * count bytes
// (trailing bytes are ignored). A file is read as ASCII only when it starts with "solid" and its first
// bytes are text, because many binary exporters also start their header with "solid". ASCII:
// `solid [name] (facet normal n n n outer loop vertex x y z (x3) endloop endfacet)* endsolid [name]`,
// keywords in any case, several solids in a row allowed. STL stores each triangle's corners
// separately; corners with bit-identical coordinates (0 and -0 counted equal) are welded into one
// vertex, so the mesh is indexed and its normals are smooth. Facet normals are ignored.
bool readStl(std::string_view bytes, const std::string& name, TriangleMesh* out, std::string* error);

// Object File Format, ASCII: "OFF" (also COFF, NOFF, CNOFF, STOFF ...: per-vertex extras are ignored),
// then "vertices faces [edges]" (on the OFF line or the next), one vertex per line (first three
// numbers used), one face per line as "n i0 ... i(n-1) [colour]" with 0-based indices. '#' comments and
// blank lines are allowed anywhere. Binary OFF and 4OFF/nOFF are refused.
bool readOff(std::string_view bytes, const std::string& name, TriangleMesh* out, std::string* error);

}  // namespace ug
