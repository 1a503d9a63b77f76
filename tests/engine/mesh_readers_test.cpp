// The bounded model readers (mesh/mesh_readers.h): exact results for tiny hand-made files of every
// format and encoding, and one regression test per class of bad input, each asserting that the error
// names the file, the element (or line) and the reason. The readers run on memory; a few cases go
// through loadMeshFile and the glTF path on disk.
#include "mesh/mesh_readers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "io/gltf_mesh_io.h"
#include "mesh/mesh_loader.h"
#include "mesh_test_util.h"

namespace ug {
namespace {

using Reader = bool (*)(std::string_view, const std::string&, TriangleMesh*, std::string*);

struct Read {
    bool ok = false;
    TriangleMesh mesh;
    std::string error;
};

// Runs `reader`; on failure also checks that the output mesh was left as it was.
Read read(Reader reader, std::string_view bytes, const std::string& name) {
    Read result;
    result.mesh.positions = {glm::vec3(42.0f)};  // a sentinel the reader must not touch on failure
    result.ok = reader(bytes, name, &result.mesh, &result.error);
    if (!result.ok) {
        EXPECT_EQ(result.mesh.positions.size(), 1u) << "output touched on failure";
        EXPECT_TRUE(result.mesh.indices.empty()) << "output touched on failure";
    }
    return result;
}

std::vector<float> flat(const std::vector<glm::vec3>& points) {
    std::vector<float> values;
    for (const glm::vec3& p : points) values.insert(values.end(), {p.x, p.y, p.z});
    return values;
}

void expectContains(const std::string& text, const std::string& part) {
    EXPECT_NE(text.find(part), std::string::npos) << "'" << text << "' lacks '" << part << "'";
}

// Little- or big-endian binary builder for PLY and STL test files.
class Bytes {
  public:
    explicit Bytes(bool big_endian = false) : big_(big_endian) {}
    template <typename T>
    Bytes& put(T value) {
        char raw[sizeof(T)];
        std::memcpy(raw, &value, sizeof(T));
        if (big_ != (std::endian::native == std::endian::big)) std::reverse(raw, raw + sizeof(T));
        data_.append(raw, sizeof(T));
        return *this;
    }
    Bytes& text(std::string_view s) {
        data_.append(s);
        return *this;
    }
    const std::string& str() const { return data_; }

  private:
    bool big_;
    std::string data_;
};

const float kNaN = std::numeric_limits<float>::quiet_NaN();

// ---- OBJ ---------------------------------------------------------------------------------------------

TEST(ObjReader, CornerFormsRelativeIndicesQuadsCommentsAndCrLf) {
    const std::string obj =
        "# exported by hand\r\n"
        "mtllib scene.mtl\r\n"
        "o thing\r\n"
        "v 0 0 0\r\n"
        "v 1 0 0 # trailing comment\r\n"
        "v 1 1 0 1.0\r\n"  // w is ignored
        "v +0 1 0\r\n"
        "vt 0 0\r\n"
        "vn 0 0 1\r\n"
        "g group\r\n"
        "usemtl stone\r\n"
        "s off\r\n"
        "f 1/1/1 2/1/1 3/1/1 4/1/1\r\n"  // quad -> (0 1 2) (0 2 3)
        "v 0 0 1\r\n"
        "f -5//1 -4//1 -1//1\r\n"   // relative: 5 vertices so far -> 0 1 4
        "f 2/1 \\\r\n 3/1 5/1\r\n"  // continued line -> 1 2 4
        "l 1 2\r\n"
        "p 1\r\n";
    const Read r = read(&readObj, obj, "thing.obj");
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(flat(r.mesh.positions), (std::vector<float>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1}));
    EXPECT_EQ(r.mesh.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 1, 4, 1, 2, 4}));
    EXPECT_EQ(r.mesh.normals.size(), 5u);
}

TEST(ObjReader, FaceMayReferToALaterVertex) {
    const Read r = read(&readObj, "f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", "later.obj");
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(r.mesh.indices, (std::vector<uint32_t>{0, 1, 2}));
}

TEST(MeshReaders, Utf8ByteOrderMarkIsSkipped) {
    const std::string bom = "\xEF\xBB\xBF";
    EXPECT_TRUE(read(&readObj, bom + "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "bom.obj").ok);
    EXPECT_TRUE(read(&readOff, bom + "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "bom.off").ok);
    EXPECT_TRUE(read(&readStl,
                     bom +
                         "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                         "endloop\nendfacet\nendsolid s\n",
                     "bom.stl")
                    .ok);
}

TEST(ObjReader, NaNVertexNamesLineAndVertex) {
    const Read r = read(&readObj, "v 0 0 0\nv 1 0 0\nv nan 0 0\nf 1 2 3\n", "rock.obj");
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.error, "rock.obj: line 3: vertex 3 has a non-finite x coordinate (nan)");

    // Finite as a double, infinite as a float.
    const Read big = read(&readObj, "v 0 0 0\nv 1 0 0\nv 0 1e39 0\nf 1 2 3\n", "rock.obj");
    EXPECT_FALSE(big.ok);
    EXPECT_EQ(big.error, "rock.obj: line 3: vertex 3 has a non-finite y coordinate (1e39)");
}

TEST(ObjReader, OutOfRangeNegativeAndZeroIndicesAreErrors) {
    const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    Read r = read(&readObj, vertices + "f 1 2 3\nf 1 2 9\n", "rock.obj");
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.error, "rock.obj: line 5: face 2 refers to vertex 9 but the file has 3 vertices");

    r = read(&readObj, vertices + "f -1 -2 -4\n", "rock.obj");
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.error, "rock.obj: line 4: face 1 refers to vertex -4 but only 3 vertices precede it");

    r = read(&readObj, vertices + "f 0 1 2\n", "rock.obj");
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.error, "rock.obj: line 4: face 1 refers to vertex 0 (OBJ indices start at 1)");
}

TEST(ObjReader, DegenerateAndMalformedStatementsAreErrors) {
    const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    Read r = read(&readObj, vertices + "f 1 2\n", "bad.obj");
    EXPECT_EQ(r.error, "bad.obj: line 4: face 1 has 2 vertices (a face needs at least 3)");
    r = read(&readObj, vertices + "f 1 2 x/1\n", "bad.obj");
    expectContains(r.error, "bad.obj: line 4: face 1: 'x/1' is not a corner");
    r = read(&readObj, "v 1 2\n", "bad.obj");
    EXPECT_EQ(r.error, "bad.obj: line 1: vertex 1 has only 2 coordinates (needs x y z)");
    r = read(&readObj, "v 1 2 three\n", "bad.obj");
    EXPECT_EQ(r.error, "bad.obj: line 1: vertex 1: 'three' is not a number");
    r = read(&readObj, vertices, "bad.obj");
    EXPECT_EQ(r.error, "bad.obj: no triangles (the file has 3 vertices and no faces)");
    r = read(&readObj, "", "empty.obj");
    expectContains(r.error, "empty.obj: no triangles");
}

// ---- PLY ---------------------------------------------------------------------------------------------

TEST(PlyReader, AsciiWithExtraPropertiesListsAndElements) {
    const std::string ply =
        "ply\r\n"
        "format ascii 1.0\r\n"
        "comment made by hand\r\n"
        "obj_info nothing\r\n"
        "element vertex 4\r\n"
        "property float x\r\n"
        "property float y\r\n"
        "property uchar red\r\n"
        "property float z\r\n"
        "property list uchar float texcoord\r\n"
        "element face 2\r\n"
        "property uchar flags\r\n"
        "property list uchar int vertex_indices\r\n"
        "element edge 1\r\n"
        "property int vertex1\r\n"
        "property int vertex2\r\n"
        "end_header\r\n"
        "0 0 255 5 2 0.5 0.5\r\n"
        "1 0 255 6 0\r\n"
        "1 1 255 7 1 0.25\r\n"
        "0 1 255 8 0\r\n"
        "7 4 0 1 2 3\r\n"
        "0 3 0 2 3\r\n"
        "0 1\r\n";
    const Read r = read(&readPly, ply, "ascii.ply");
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(flat(r.mesh.positions), (std::vector<float>{0, 0, 5, 1, 0, 6, 1, 1, 7, 0, 1, 8}));
    EXPECT_EQ(r.mesh.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 2, 3}));
}

// The same model in both byte orders: mixed coordinate types, skipped scalars and lists, an extra
// fixed-size element before the faces and an extra element with a list after them.
std::string binaryPly(bool big_endian) {
    Bytes b(big_endian);
    b.text("ply\nformat ");
    b.text(big_endian ? "binary_big_endian" : "binary_little_endian");
    b.text(
        " 1.0\n"
        "element vertex 3\n"
        "property double x\n"
        "property uchar confidence\n"
        "property short y\n"
        "property float z\n"
        "element material 2\n"
        "property uchar r\n"
        "property int g\n"
        "element face 1\n"
        "property list uint int vertex_indices\n"
        "property list uchar uchar other\n"
        "element edge 1\n"
        "property list ushort ushort ends\n"
        "end_header\n");
    b.put(1.5).put(uint8_t(7)).put(int16_t(-2)).put(3.25f);
    b.put(0.0).put(uint8_t(0)).put(int16_t(4)).put(1.0f);
    b.put(-1.0).put(uint8_t(255)).put(int16_t(0)).put(0.0f);
    b.put(uint8_t(1)).put(int32_t(-7)).put(uint8_t(2)).put(int32_t(99));
    b.put(uint32_t(3))
        .put(int32_t(2))
        .put(int32_t(0))
        .put(int32_t(1))
        .put(uint8_t(2))
        .put(uint8_t(9))
        .put(uint8_t(9));
    b.put(uint16_t(2)).put(uint16_t(0)).put(uint16_t(1));
    return b.str();
}

TEST(PlyReader, BinaryLittleAndBigEndianWithSkippedData) {
    for (const bool big : {false, true}) {
        SCOPED_TRACE(big ? "big endian" : "little endian");
        const Read r = read(&readPly, binaryPly(big), "binary.ply");
        ASSERT_TRUE(r.ok) << r.error;
        EXPECT_EQ(flat(r.mesh.positions), (std::vector<float>{1.5f, -2, 3.25f, 0, 4, 1, -1, 0, 0}));
        EXPECT_EQ(r.mesh.indices, (std::vector<uint32_t>{2, 0, 1}));
    }
}

TEST(PlyReader, HeaderWithoutEndHeaderEndsWithAnError) {
    // The 38-byte fuzz case that made OpenMesh's reader loop forever growing to 9 GB.
    const std::string fuzz = "ply\nformat ascii 1.0\nelement vertex 3\n";
    ASSERT_EQ(fuzz.size(), 38u);
    Read r = read(&readPly, fuzz, "rock.ply");
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.error, "rock.ply: the header has no end_header line (the file ends after 38 bytes)");

    // A header that goes on and on is cut at kMaxPlyHeaderBytes.
    std::string endless = "ply\nformat ascii 1.0\n";
    while (endless.size() < 2 * kMaxPlyHeaderBytes) endless += "comment still the header\n";
    r = read(&readPly, endless, "rock.ply");
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.error, "rock.ply: no end_header line within the first 65536 bytes (kMaxPlyHeaderBytes)");
}

TEST(PlyReader, HugeDeclaredCountIsRefusedBeforeAllocating) {
    const std::string header =
        "ply\nformat binary_little_endian 1.0\nelement vertex 1099511627776\nproperty float x\nproperty "
        "float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const Read r = read(&readPly, header + std::string(12, '\0'), "rock.ply");
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.error, "rock.ply: header line 3: declares 1099511627776 vertices but the file has only " +
                           std::to_string(header.size() + 12) + " bytes");

    // The count is the reported problem even when the header also lacks a face element.
    const std::string no_faces =
        "ply\nformat binary_little_endian 1.0\nelement vertex 1099511627776\nproperty float x\n"
        "property float y\nproperty float z\nend_header\n";
    const Read n = read(&readPly, no_faces, "huge.ply");
    EXPECT_EQ(n.error, "huge.ply: header line 3: declares 1099511627776 vertices but the file has only " +
                           std::to_string(no_faces.size()) + " bytes");

    // Same in ASCII, for the faces.
    const Read a =
        read(&readPly,
             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
             "element face 4000000000\nproperty list uchar int vertex_indices\nend_header\n"
             "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
             "rock.ply");
    EXPECT_FALSE(a.ok);
    expectContains(a.error, "rock.ply: header line 7: declares 4000000000 faces but the file has only");
}

TEST(PlyReader, ElementWithoutPropertiesIsSkippedWhateverItsCount) {
    // Occupies no bytes, so a huge count is legal and must not be walked one by one.
    const std::string ply =
        "ply\nformat ascii 1.0\nelement nothing 9000000000000000000\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\nelement face 1\nproperty list uchar int "
        "vertex_index\nend_header\n"
        "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    const Read r = read(&readPly, ply, "empty_element.ply");
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(r.mesh.indices, (std::vector<uint32_t>{0, 1, 2}));
}

TEST(PlyReader, TruncatedNonFiniteAndBadIndicesNameTheElement) {
    const std::string header =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";
    Bytes vertices;
    vertices.put(0.0f).put(0.0f).put(0.0f).put(1.0f).put(0.0f).put(0.0f).put(0.0f).put(1.0f).put(0.0f);

    // The first face is long enough that the count check passes; the second is missing.
    Bytes one_face;
    one_face.put(uint8_t(10));
    for (int i = 0; i < 10; ++i) one_face.put(int32_t(i % 3));
    Read r = read(&readPly, header + vertices.str() + one_face.str(), "rock.ply");
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.error, "rock.ply: truncated in the face list at face 1 of 2");

    Bytes nan_vertices;
    nan_vertices.put(0.0f).put(0.0f).put(0.0f).put(1.0f).put(0.0f).put(kNaN).put(0.0f).put(1.0f).put(0.0f);
    Bytes faces;
    faces.put(uint8_t(3)).put(int32_t(0)).put(int32_t(1)).put(int32_t(2));
    faces.put(uint8_t(3)).put(int32_t(0)).put(int32_t(2)).put(int32_t(1));
    r = read(&readPly, header + nan_vertices.str() + faces.str(), "rock.ply");
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.error, "rock.ply: vertex 1 has a non-finite z coordinate (nan)");

    Bytes bad_faces;
    bad_faces.put(uint8_t(3)).put(int32_t(0)).put(int32_t(1)).put(int32_t(2));
    bad_faces.put(uint8_t(3)).put(int32_t(0)).put(int32_t(-1)).put(int32_t(1));
    r = read(&readPly, header + vertices.str() + bad_faces.str(), "rock.ply");
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.error, "rock.ply: face 1 refers to vertex -1 but the file has 3 vertices");

    const std::string ascii =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
        "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n";
    r = read(&readPly, ascii, "rock.ply");
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.error, "rock.ply: line 13: face 0 refers to vertex 7 but the file has 3 vertices");

    r = read(&readPly,
             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
             "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
             "0 0 0\n1 0 oops\n0 1 0\n3 0 1 2\n",
             "rock.ply");
    EXPECT_EQ(r.error, "rock.ply: line 11: vertex 1: 'oops' is not a number");

    r = read(&readPly,
             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
             "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
             "0 0 0\n1 0 0\n0 1 0\n2 0 1 9 9 9\n",
             "rock.ply");
    EXPECT_EQ(r.error, "rock.ply: line 13: face 0 has 2 vertices (a face needs at least 3)");
}

TEST(PlyReader, HeaderProblemsAreErrors) {
    Read r = read(&readPly, "PLY\n", "x.ply");
    EXPECT_EQ(r.error, "x.ply: not a PLY file (the first line is not \"ply\")");
    r = read(&readPly,
             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nend_header\n"
             "0 0\n1 0\n0 1\n",
             "x.ply");
    EXPECT_EQ(r.error, "x.ply: no face element (a point cloud has no triangles)");
    r = read(&readPly,
             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nelement face 0\n"
             "property list uchar int vertex_indices\nend_header\n0 0\n1 0\n0 1\n",
             "x.ply");
    EXPECT_EQ(r.error, "x.ply: header line 3: the vertex element has no 'z' property");
    r = read(&readPly, "ply\nformat ascii 1.0\nelement vertex 3\nproperty quad x\nend_header\n", "x.ply");
    EXPECT_EQ(r.error, "x.ply: header line 4: unknown property type 'quad'");
    r = read(&readPly, "ply\nformat binary_middle_endian 1.0\nend_header\n", "x.ply");
    expectContains(r.error, "x.ply: header line 2: unknown format 'binary_middle_endian'");
}

// ---- STL ---------------------------------------------------------------------------------------------

// Two triangles sharing an edge; the shared corner (1, 0, 0) is written once as (1, -0, 0).
std::string binaryStl(const std::string& comment, float poison = 0.0f) {
    Bytes b;
    std::string header = comment;
    header.resize(80, ' ');
    b.text(header).put(uint32_t(2));
    const float corners[2][3][3] = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
                                    {{1, -0.0f, 0}, {1, 1, 0}, {0, 1, poison}}};
    for (const auto& facet : corners) {
        b.put(0.0f).put(0.0f).put(1.0f);
        for (const auto& corner : facet) b.put(corner[0]).put(corner[1]).put(corner[2]);
        b.put(uint16_t(0));
    }
    return b.str();
}

TEST(StlReader, BinaryStartingWithSolidIsReadAsBinaryAndWelded) {
    const std::string stl = binaryStl("solid this header lies, the file is binary");
    ASSERT_EQ(stl.size(), 84u + 2 * 50);
    Read r = read(&readStl, stl, "binary.stl");
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(flat(r.mesh.positions), (std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}));
    EXPECT_EQ(r.mesh.indices, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2}));

    // Trailing bytes after the declared triangles are tolerated.
    r = read(&readStl, stl + "xyz", "binary.stl");
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(r.mesh.indices, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2}));
}

TEST(StlReader, AsciiInAnyCaseAndSeveralSolids) {
    const std::string stl =
        "solid first part\r\n"
        "  facet normal 0 0 1\r\n    outer loop\r\n      vertex 0 0 0\r\n      vertex 1 0 0\r\n"
        "      vertex 0 1 0\r\n    endloop\r\n  endfacet\r\n"
        "endsolid first part\r\n"
        "SOLID second\r\n"
        "FACET NORMAL nan nan nan\r\nOUTER LOOP\r\nVERTEX 1 0 0\r\nVERTEX 1 1 0\r\nVERTEX 0 1 "
        "0\r\nENDLOOP\r\n"
        "ENDFACET\r\n"
        "ENDSOLID second\r\n";
    const Read r = read(&readStl, stl, "ascii.stl");
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(flat(r.mesh.positions), (std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}));
    EXPECT_EQ(r.mesh.indices, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2}));
}

TEST(StlReader, NaNVertexIsAnErrorInBothEncodings) {
    Read r = read(&readStl, binaryStl("made by hand", kNaN), "rock.stl");
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.error, "rock.stl: facet 1: vertex 2 has a non-finite z coordinate (nan)");

    const std::string ascii =
        "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex nan 0 0\nvertex 0 1 0\nendloop\n"
        "endfacet\nendsolid s\n";
    r = read(&readStl, ascii, "rock.stl");
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.error, "rock.stl: line 5: facet 0: vertex 1 has a non-finite x coordinate (nan)");
}

TEST(StlReader, BinaryCountLargerThanTheFileIsRefused) {
    Bytes stl;
    stl.text(std::string(80, ' ')).put(uint32_t(1000)).text(std::string(50, '\0'));  // one facet of 1000
    const Read r = read(&readStl, stl.str(), "rock.stl");
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(
        r.error,
        "rock.stl: binary STL header declares 1000 triangles but the file has only 134 bytes (50084 needed)");

    const Read tiny = read(&readStl, "abc", "tiny.stl");
    expectContains(tiny.error, "tiny.stl: not an ASCII STL");
}

TEST(StlReader, TruncatedOrMalformedAsciiSaysWhere) {
    const std::string facet =
        "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";
    Read r = read(&readStl, "solid s\n" + facet, "cut.stl");
    EXPECT_EQ(r.error, "cut.stl: truncated after facet 1 (the file ends without 'endsolid')");
    r = read(&readStl, "solid s\n" + facet + "facet normal 0 0 1\nouter loop\nvertex 0 0", "cut.stl");
    EXPECT_EQ(r.error, "cut.stl: truncated in facet 1 (the file ends inside its vertex)");
    r = read(&readStl, "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n",
             "two.stl");
    EXPECT_EQ(r.error, "two.stl: line 6: facet 0 has 2 vertices (a facet needs 3)");
}

// ---- OFF ---------------------------------------------------------------------------------------------

TEST(OffReader, CommentsBlankLinesPolygonsAndFaceColours) {
    const std::string off =
        "# leading comment\n"
        "OFF\n"
        "# counts follow\n"
        "5 2 0\n"
        "0 0 0\n"
        "1 0 0\n"
        "1 1 0 # a comment after a vertex\n"
        "\n"
        "0 1 0\n"
        "0.5 0.5 1\n"
        "4 0 1 2 3 255 0 0\n"  // quad with a colour
        "3 0 1 4\n";
    Read r = read(&readOff, off, "thing.off");
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(flat(r.mesh.positions),
              (std::vector<float>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5f, 0.5f, 1}));
    EXPECT_EQ(r.mesh.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 1, 4}));

    // Counts on the keyword line; a colour variant with per-vertex extras.
    r = read(&readOff, "COFF 3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n3 0 1 2\n",
             "c.off");
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(r.mesh.indices, (std::vector<uint32_t>{0, 1, 2}));
}

TEST(OffReader, BadCountsAreErrors) {
    Read r = read(&readOff, "OFF\n-3 1 0\n", "bad.off");
    EXPECT_EQ(r.error,
              "bad.off: line 2: bad vertex count '-3' (want \"<vertices> <faces> [<edges>]\", counts >= 0)");
    r = read(&readOff, "OFF\n3 many 0\n", "bad.off");
    expectContains(r.error, "bad.off: line 2: bad face count 'many'");
    const std::string body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    r = read(&readOff, "OFF\n3 99 0\n" + body, "bad.off");
    EXPECT_EQ(r.error, "bad.off: line 2: declares 99 faces but the file has only " +
                           std::to_string(std::string("OFF\n3 99 0\n").size() + body.size()) + " bytes");
    r = read(&readOff, "OFF\n99999999999 1 0\n" + body, "bad.off");
    expectContains(r.error, "bad.off: line 2: declares 99999999999 vertices but the file has only");
}

TEST(OffReader, TruncatedOutOfRangeAndNonFiniteNameTheElement) {
    const std::string vertices = "0 0 0\n1 0 0\n0 1 0\n";
    // The first face carries a long colour so the count check passes; the second face is missing.
    Read r = read(&readOff, "OFF\n3 2 0\n" + vertices + "3 0 1 2 0.25 0.25 0.25 1.0\n", "cut.off");
    EXPECT_EQ(r.error, "cut.off: truncated in the face list at face 1 of 2");
    r = read(&readOff, "OFF\n3 1 0\n" + vertices + "3 0 1 3\n", "bad.off");
    EXPECT_EQ(r.error, "bad.off: line 6: face 0 refers to vertex 3 but the file has 3 vertices");
    r = read(&readOff, "OFF\n3 1 0\n0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n", "bad.off");
    EXPECT_EQ(r.error, "bad.off: line 4: vertex 1 has a non-finite y coordinate (inf)");
    r = read(&readOff, "OFF\n3 1 0\n" + vertices + "2 0 1 # degenerate\n", "bad.off");
    EXPECT_EQ(r.error, "bad.off: line 6: face 0 has 2 vertices (a face needs at least 3)");
    r = read(&readOff, "4OFF\n", "bad.off");
    EXPECT_EQ(r.error, "bad.off: '4OFF' (vertices that are not 3D) is not supported");
    r = read(&readOff, "ply\n", "bad.off");
    EXPECT_EQ(r.error, "bad.off: not an OFF file (the first word is 'ply', want OFF)");
}

// ---- Through the loader and the glTF path ------------------------------------------------------------

TEST(MeshReaders, LoaderPrefixesThePathAndLeavesOutUntouched) {
    const std::string path = test::tempPath("bad_index.obj");
    test::writeText(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
    TriangleMesh mesh = test::unitCube();
    std::string error;
    EXPECT_FALSE(loadMeshFile(path, &mesh, &error));
    EXPECT_EQ(error, path + ": line 4: face 1 refers to vertex 4 but the file has 3 vertices");
    EXPECT_EQ(mesh.triangleCount(), 12u);

    const std::string ply = test::tempPath("UPPER.PLY");
    test::writeText(ply, binaryPly(false));
    ASSERT_TRUE(loadMeshFile(ply, &mesh, &error)) << error;
    EXPECT_EQ(mesh.triangleCount(), 1u);
    EXPECT_EQ(mesh.normals.size(), 3u);
}

TEST(MeshReaders, FileOverTheSizeLimitIsRefusedBeforeReading) {
    // Sparse files: the size is what counts, and nothing is read, so no disk space or memory is used.
    for (const char* name : {"huge.obj", "huge.glb"}) {
        const std::string path = test::tempPath(name);
        test::writeText(path, "");
        std::filesystem::resize_file(path, kMaxMeshFileBytes + 1);
        TriangleMesh mesh;
        std::string error;
        EXPECT_FALSE(loadMeshFile(path, &mesh, &error));
        EXPECT_EQ(error, path +
                             ": the file has 2147483649 bytes; model files are limited to 2147483648 bytes "
                             "(2 GiB, kMaxMeshFileBytes)");
        std::filesystem::remove(path);
    }
}

std::vector<char> readAll(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Writes the unit cube as GLB, lets `patch` change the file's bytes (given the offset of the binary chunk's
// data: POSITION at 0, NORMAL at 96, uint32 indices at 192), and returns the path of the patched file.
template <typename Patch>
std::string patchedCubeGlb(const std::string& name, Patch patch) {
    const TriangleMesh cube = test::unitCube();
    const std::string path = test::tempPath(name);
    std::string error;
    EXPECT_TRUE(writeGltfMeshes(path, {{"cube", &cube}}, &error)) << error;
    std::vector<char> bytes = readAll(path);
    uint32_t json_length = 0;
    std::memcpy(&json_length, bytes.data() + 12, 4);
    patch(bytes, 20 + size_t(json_length) + 8);
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(bytes.data(), std::streamsize(bytes.size()));
    return path;
}

TEST(MeshReaders, GltfNonFinitePositionAndBadIndexNameMeshPrimitiveAndElement) {
    const std::string nan_path = patchedCubeGlb("nan_position.glb", [](std::vector<char>& bytes, size_t bin) {
        std::memcpy(&bytes[bin + 12 * 3 + 4], &kNaN, 4);  // vertex 3, y
    });
    TriangleMesh mesh;
    std::string error;
    EXPECT_FALSE(loadMeshFile(nan_path, &mesh, &error));
    EXPECT_EQ(error,
              nan_path + ": mesh 0 primitive 0: POSITION vertex 3 has a non-finite y coordinate (nan)");

    const std::string index_path = patchedCubeGlb("bad_index.glb", [](std::vector<char>& bytes, size_t bin) {
        const uint32_t index = 99;
        std::memcpy(&bytes[bin + 192 + 4 * 5], &index, 4);  // index 5
    });
    EXPECT_FALSE(loadMeshFile(index_path, &mesh, &error));
    EXPECT_EQ(error, index_path + ": mesh 0 primitive 0: index 5 is 99 but POSITION has 8 vertices");

    // 35 indices (the JSON edited in place, same length): not whole triangles.
    const std::string count_path =
        patchedCubeGlb("partial_triangle.glb", [](std::vector<char>& bytes, size_t) {
            const std::string from = "\"count\":36", to = "\"count\":35";
            const auto at = std::search(bytes.begin(), bytes.end(), from.begin(), from.end());
            ASSERT_NE(at, bytes.end());
            std::copy(to.begin(), to.end(), at);
        });
    EXPECT_FALSE(loadMeshFile(count_path, &mesh, &error));
    EXPECT_EQ(error,
              count_path + ": mesh 0 primitive 0: index accessor 2 has 35 indices, not a multiple of 3");
}

TEST(MeshReaders, GltfNodeReachedTwiceIsAnError) {
    // A node listed many times at every level would make the walk exponential; glTF forbids it.
    const std::string path = test::tempPath("shared_child.gltf");
    test::writeText(path, R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],)"
                          R"("nodes":[{"children":[1,1]},{}]})");
    TriangleMesh mesh;
    std::string error;
    EXPECT_FALSE(loadMeshFile(path, &mesh, &error));
    EXPECT_EQ(error, path + ": node 1 is reached twice (glTF nodes must form trees)");
}

}  // namespace
}  // namespace ug
