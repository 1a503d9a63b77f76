// Stanford PLY reader (contract in mesh_readers.h). The header is parsed first and every element's
// count is checked against the bytes after it, so nothing is sized from an unchecked number; then
// the elements are read in header order by one routine that is generic over the encoding (ASCII
// tokens or binary of either byte order).
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <vector>

#include "mesh/mesh_reader_detail.h"
#include "mesh/mesh_readers.h"

namespace ug {

namespace {

using namespace mesh_reader;

enum class Scalar : uint8_t { Int8, Uint8, Int16, Uint16, Int32, Uint32, Float32, Float64 };

bool scalarFromName(std::string_view name, Scalar* type) {
    // Both spellings are in use: the original names (char, uchar, ...) and the sized ones (int8, ...).
    static constexpr struct {
        std::string_view name;
        Scalar type;
    } kNames[] = {{"char", Scalar::Int8},      {"int8", Scalar::Int8},       {"uchar", Scalar::Uint8},
                  {"uint8", Scalar::Uint8},    {"short", Scalar::Int16},     {"int16", Scalar::Int16},
                  {"ushort", Scalar::Uint16},  {"uint16", Scalar::Uint16},   {"int", Scalar::Int32},
                  {"int32", Scalar::Int32},    {"uint", Scalar::Uint32},     {"uint32", Scalar::Uint32},
                  {"float", Scalar::Float32},  {"float32", Scalar::Float32}, {"double", Scalar::Float64},
                  {"float64", Scalar::Float64}};
    for (const auto& entry : kNames)
        if (entry.name == name) {
            *type = entry.type;
            return true;
        }
    return false;
}

size_t scalarSize(Scalar type) {
    switch (type) {
        case Scalar::Int8:
        case Scalar::Uint8:
            return 1;
        case Scalar::Int16:
        case Scalar::Uint16:
            return 2;
        case Scalar::Int32:
        case Scalar::Uint32:
        case Scalar::Float32:
            return 4;
        case Scalar::Float64:
            return 8;
    }
    return 1;
}

bool isInteger(Scalar type) {
    return type != Scalar::Float32 && type != Scalar::Float64;
}

struct Property {
    std::string name;
    Scalar type = Scalar::Float32;  // the item type for a list
    bool is_list = false;
    Scalar count_type = Scalar::Uint8;
};

struct Element {
    std::string name;
    uint64_t count = 0;
    size_t line = 0;  // header line, for messages
    std::vector<Property> properties;
};

enum class Encoding { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct Header {
    Encoding encoding = Encoding::Ascii;
    std::vector<Element> elements;
    size_t data_offset = 0;  // first byte after the end_header line
    size_t lines = 0;        // header lines, so ASCII data lines are numbered as in the file
};

std::string headerLine(size_t line) {
    return "header line " + std::to_string(line) + ": ";
}

bool parseHeader(std::string_view bytes, Header* header, std::string* why) {
    // Only the first kMaxPlyHeaderBytes are ever searched: a file without end_header (the fuzz case
    // that made OpenMesh loop) ends here with an error after at most that much work.
    const std::string_view region = bytes.substr(0, std::min(bytes.size(), kMaxPlyHeaderBytes));
    size_t pos = 0, line = 0;
    bool have_format = false;
    for (;;) {
        if (pos >= region.size()) break;
        size_t eol = region.find('\n', pos);
        std::string_view text;
        if (eol == std::string_view::npos) {
            // An unterminated last line only counts if it is the file's end (not the region's).
            if (region.size() != bytes.size()) break;
            text = region.substr(pos);
            eol = region.size() - 1;
        } else {
            text = region.substr(pos, eol - pos);
        }
        ++line;
        pos = eol + 1;
        if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
        TextScanner scan(text, 0, false);
        const std::string_view keyword = scan.lineToken();
        if (line == 1) {
            if (keyword != "ply" || !scan.lineToken().empty()) {
                *why = "not a PLY file (the first line is not \"ply\")";
                return false;
            }
            continue;
        }
        if (keyword == "end_header") {
            if (!have_format) {
                *why = headerLine(line) + "the header has no format line";
                return false;
            }
            header->data_offset = pos;
            header->lines = line;
            return true;
        }
        if (keyword.empty() || keyword == "comment" || keyword == "obj_info") continue;
        if (keyword == "format") {
            const std::string_view encoding = scan.lineToken();
            if (encoding == "ascii") {
                header->encoding = Encoding::Ascii;
            } else if (encoding == "binary_little_endian") {
                header->encoding = Encoding::BinaryLittleEndian;
            } else if (encoding == "binary_big_endian") {
                header->encoding = Encoding::BinaryBigEndian;
            } else {
                *why = headerLine(line) + "unknown format " + shown(encoding) +
                       " (want ascii, binary_little_endian or binary_big_endian)";
                return false;
            }
            have_format = true;
        } else if (keyword == "element") {
            Element element;
            element.name = std::string(scan.lineToken());
            element.line = line;
            const std::string_view count = scan.lineToken();
            int64_t value = 0;
            if (element.name.empty() || !parseInteger(count, &value) || value < 0) {
                *why = headerLine(line) + "bad element line (want \"element <name> <count>\", count >= 0)";
                return false;
            }
            element.count = uint64_t(value);
            header->elements.push_back(std::move(element));
        } else if (keyword == "property") {
            if (header->elements.empty()) {
                *why = headerLine(line) + "property before any element";
                return false;
            }
            Property property;
            std::string_view type = scan.lineToken();
            if (type == "list") {
                property.is_list = true;
                const std::string_view count_type = scan.lineToken();
                if (!scalarFromName(count_type, &property.count_type) || !isInteger(property.count_type)) {
                    *why =
                        headerLine(line) + "list count type " + shown(count_type) + " is not an integer type";
                    return false;
                }
                type = scan.lineToken();
            }
            if (!scalarFromName(type, &property.type)) {
                *why = headerLine(line) + "unknown property type " + shown(type);
                return false;
            }
            property.name = std::string(scan.lineToken());
            if (property.name.empty()) {
                *why = headerLine(line) + "property without a name";
                return false;
            }
            header->elements.back().properties.push_back(std::move(property));
        } else {
            *why = headerLine(line) + "unknown header keyword " + shown(keyword);
            return false;
        }
    }
    if (region.size() == bytes.size())
        *why = "the header has no end_header line (the file ends after " + std::to_string(bytes.size()) +
               " bytes)";
    else
        *why = "no end_header line within the first " + std::to_string(kMaxPlyHeaderBytes) +
               " bytes (kMaxPlyHeaderBytes)";
    return false;
}

enum class Got { Ok, End, Bad };

// ASCII data: whitespace-separated tokens (the one-element-per-line layout is not relied on).
class AsciiSource {
  public:
    AsciiSource(std::string_view data, size_t first_line) : scan_(data, 0, false, first_line) {}

    Got real(Scalar, double* value) {
        token_ = scan_.token();
        if (token_.empty()) return Got::End;
        return parseReal(token_, value) ? Got::Ok : Got::Bad;
    }
    Got integer(Scalar, int64_t* value) {
        token_ = scan_.token();
        if (token_.empty()) return Got::End;
        return parseInteger(token_, value) ? Got::Ok : Got::Bad;
    }
    Got skip(Scalar type) {
        double unused = 0.0;
        return real(type, &unused);
    }
    // Whether `items` more values can still be in the data (each takes a character and a separator).
    bool mayHold(uint64_t items, Scalar) const { return items <= (scan_.remaining() + 1) / 2; }
    bool skipFixed(uint64_t, size_t) { return false; }  // no fixed layout in text
    std::string where() const { return "line " + std::to_string(scan_.line()) + ": "; }
    std::string_view token() const { return token_; }

  private:
    TextScanner scan_;
    std::string_view token_;
};

// Binary data in either byte order.
class BinarySource {
  public:
    BinarySource(std::string_view data, bool big_endian)
        : p_(data.data()),
          end_(data.data() + data.size()),
          swap_(big_endian != (std::endian::native == std::endian::big)) {}

    Got real(Scalar type, double* value) {
        const size_t size = scalarSize(type);
        if (size_t(end_ - p_) < size) return Got::End;
        unsigned char raw[8];
        std::memcpy(raw, p_, size);
        p_ += size;
        if (swap_) std::reverse(raw, raw + size);
        switch (type) {
            case Scalar::Int8:
                *value = double(int8_t(raw[0]));
                break;
            case Scalar::Uint8:
                *value = double(raw[0]);
                break;
            case Scalar::Int16:
                *value = double(load<int16_t>(raw));
                break;
            case Scalar::Uint16:
                *value = double(load<uint16_t>(raw));
                break;
            case Scalar::Int32:
                *value = double(load<int32_t>(raw));
                break;
            case Scalar::Uint32:
                *value = double(load<uint32_t>(raw));
                break;
            case Scalar::Float32:
                *value = double(load<float>(raw));
                break;
            case Scalar::Float64:
                *value = load<double>(raw);
                break;
        }
        return Got::Ok;
    }
    Got integer(Scalar type, int64_t* value) {
        // Only integer types reach here (the header check), and every one of them is exact in a double.
        double v = 0.0;
        const Got got = real(type, &v);
        *value = int64_t(v);
        return got;
    }
    Got skip(Scalar type) {
        const size_t size = scalarSize(type);
        if (size_t(end_ - p_) < size) return Got::End;
        p_ += size;
        return Got::Ok;
    }
    bool mayHold(uint64_t items, Scalar type) const {
        return items <= uint64_t(end_ - p_) / scalarSize(type);
    }
    bool skipFixed(uint64_t count, size_t bytes_each) {
        // The header check guarantees the bytes are there; test anyway rather than trust it.
        if (bytes_each == 0 || count > uint64_t(end_ - p_) / bytes_each) return false;
        p_ += count * bytes_each;
        return true;
    }
    std::string where() const { return {}; }
    std::string_view token() const { return {}; }

  private:
    template <typename T>
    static T load(const unsigned char* raw) {
        T value;
        std::memcpy(&value, raw, sizeof(T));
        return value;
    }

    const char* p_;
    const char* end_;
    bool swap_;
};

// What the reader takes from the two elements it understands.
struct Layout {
    int vertex = -1, face = -1;  // element numbers
    int xyz[3] = {-1, -1, -1};   // property numbers in the vertex element
    int indices = -1;            // the index list in the face element
};

bool findLayout(const Header& header, Layout* layout, std::string* why) {
    for (size_t e = 0; e < header.elements.size(); ++e) {
        const Element& element = header.elements[e];
        int* slot = element.name == "vertex" ? &layout->vertex
                    : element.name == "face" ? &layout->face
                                             : nullptr;
        if (!slot) continue;
        if (*slot >= 0) {
            *why = headerLine(element.line) + "a second '" + element.name + "' element";
            return false;
        }
        *slot = int(e);
    }
    if (layout->vertex < 0) {
        *why = "no vertex element";
        return false;
    }
    if (layout->face < 0) {
        *why = "no face element (a point cloud has no triangles)";
        return false;
    }
    const Element& vertex = header.elements[size_t(layout->vertex)];
    for (size_t p = 0; p < vertex.properties.size(); ++p) {
        const Property& property = vertex.properties[p];
        for (int k = 0; k < 3; ++k)
            if (property.name == axisName(k)) {
                if (property.is_list) {
                    *why = headerLine(vertex.line) + "vertex property '" + property.name + "' is a list";
                    return false;
                }
                if (layout->xyz[k] < 0) layout->xyz[k] = int(p);
            }
    }
    for (int k = 0; k < 3; ++k)
        if (layout->xyz[k] < 0) {
            *why = headerLine(vertex.line) + "the vertex element has no '" + axisName(k) + "' property";
            return false;
        }
    const Element& face = header.elements[size_t(layout->face)];
    for (size_t p = 0; p < face.properties.size(); ++p) {
        const Property& property = face.properties[p];
        if (property.name != "vertex_indices" && property.name != "vertex_index") continue;
        if (!property.is_list || !isInteger(property.type)) {
            *why = headerLine(face.line) + "face property '" + property.name + "' is not a list of integers";
            return false;
        }
        layout->indices = int(p);
        break;
    }
    if (layout->indices < 0) {
        *why = headerLine(face.line) + "the face element has no 'vertex_indices' (or 'vertex_index') list";
        return false;
    }
    return true;
}

// The fewest bytes an element can take, for the check against the file size. The face index list is
// counted with 3 items: a shorter face is an error anyway, and the bound then also caps the index
// memory at a small multiple of the file.
uint64_t minElementBytes(const Element& element, bool ascii, int index_list) {
    uint64_t bytes = 0;
    for (size_t p = 0; p < element.properties.size(); ++p) {
        const Property& property = element.properties[p];
        const uint64_t items = int(p) == index_list ? 3 : 0;
        if (ascii)  // a token and a separator per value
            bytes += 2 * ((property.is_list ? 1 : 0) + (property.is_list ? items : 1));
        else
            bytes += property.is_list ? scalarSize(property.count_type) + items * scalarSize(property.type)
                                      : scalarSize(property.type);
    }
    return bytes;
}

std::string plural(const Element& element) {
    if (element.name == "vertex") return "vertices";
    if (element.name == "face") return "faces";
    return "'" + element.name + "' elements";
}

// "truncated in the face list at face 5 of 12", "truncated in element 'edge' at 2 of 5".
std::string truncatedAt(const Element& element, uint64_t i) {
    if (element.name == "vertex" || element.name == "face")
        return "truncated in the " + element.name + " list at " + element.name + " " + std::to_string(i) +
               " of " + std::to_string(element.count);
    return "truncated in element '" + element.name + "' at " + std::to_string(i) + " of " +
           std::to_string(element.count);
}

std::string elementItem(const Element& element, uint64_t i) {
    if (element.name == "vertex" || element.name == "face") return element.name + " " + std::to_string(i);
    return "element '" + element.name + "' " + std::to_string(i);
}

// Checks every element's count against the bytes after the header, all elements together. With a
// layout, each face's index list counts as at least 3 items.
bool checkCounts(const Header& header, uint64_t file_size, const Layout* layout, std::string* why) {
    const bool ascii = header.encoding == Encoding::Ascii;
    uint64_t budget =
        file_size - header.data_offset + (ascii ? 1 : 0);  // ASCII: the last value needs no separator
    for (size_t e = 0; e < header.elements.size(); ++e) {
        const Element& element = header.elements[e];
        const int index_list = layout && int(e) == layout->face ? layout->indices : -1;
        const uint64_t min_bytes = minElementBytes(element, ascii, index_list);
        *why = countExceedsFile(element.count, min_bytes, budget, plural(element), file_size);
        if (!why->empty()) {
            *why = headerLine(element.line) + *why;
            return false;
        }
        budget -= element.count * min_bytes;
    }
    return true;
}

template <typename Source>
bool readElements(Source& source, const Header& header, const Layout& layout, TriangleMesh* mesh,
                  std::string* why) {
    const uint64_t vertex_count = header.elements[size_t(layout.vertex)].count;
    std::vector<uint32_t> corners;
    auto bad = [&](const Element& element, uint64_t i, Got got) {
        if (got == Got::End)
            *why = truncatedAt(element, i);
        else
            *why =
                source.where() + elementItem(element, i) + ": " + shown(source.token()) + " is not a number";
        return false;
    };
    for (size_t e = 0; e < header.elements.size(); ++e) {
        const Element& element = header.elements[e];
        const bool is_vertex = int(e) == layout.vertex, is_face = int(e) == layout.face;
        // An element without properties occupies no bytes, whatever its count: nothing to walk.
        if (element.properties.empty()) continue;
        if (!is_vertex && !is_face) {
            const bool has_list = std::any_of(element.properties.begin(), element.properties.end(),
                                              [](const Property& p) { return p.is_list; });
            if (!has_list && source.skipFixed(element.count, size_t(minElementBytes(element, false, -1))))
                continue;
        }
        for (uint64_t i = 0; i < element.count; ++i) {
            float xyz[3] = {0.0f, 0.0f, 0.0f};
            for (size_t p = 0; p < element.properties.size(); ++p) {
                const Property& property = element.properties[p];
                if (!property.is_list) {
                    int axis = -1;
                    if (is_vertex)
                        for (int k = 0; k < 3; ++k)
                            if (layout.xyz[k] == int(p)) axis = k;
                    if (axis < 0) {
                        const Got got = source.skip(property.type);
                        if (got != Got::Ok) return bad(element, i, got);
                        continue;
                    }
                    double value = 0.0;
                    const Got got = source.real(property.type, &value);
                    if (got != Got::Ok) return bad(element, i, got);
                    xyz[axis] = float(value);
                    if (!std::isfinite(xyz[axis])) {
                        *why = source.where() + "vertex " + std::to_string(i) + " has a non-finite " +
                               axisName(axis) + " coordinate (" + valueText(value) + ")";
                        return false;
                    }
                    continue;
                }
                int64_t n = 0;
                Got got = source.integer(property.count_type, &n);
                if (got != Got::Ok) return bad(element, i, got);
                if (n < 0) {
                    *why = source.where() + elementItem(element, i) + ": list '" + property.name +
                           "' has a negative length (" + std::to_string(n) + ")";
                    return false;
                }
                if (!source.mayHold(uint64_t(n), property.type)) {
                    *why = truncatedAt(element, i) + " (its list '" + property.name + "' declares " +
                           std::to_string(n) + " values)";
                    return false;
                }
                if (!(is_face && int(p) == layout.indices)) {
                    for (int64_t k = 0; k < n; ++k)
                        if ((got = source.skip(property.type)) != Got::Ok) return bad(element, i, got);
                    continue;
                }
                if (n < 3) {
                    *why = source.where() + "face " + std::to_string(i) + " has " + std::to_string(n) +
                           " vertices (a face needs at least 3)";
                    return false;
                }
                if (mesh->triangleCount() + uint64_t(n - 2) > kMaxMeshTriangles) {
                    *why = source.where() + "face " + std::to_string(i) + ": more than " +
                           std::to_string(kMaxMeshTriangles) + " triangles (kMaxMeshTriangles)";
                    return false;
                }
                corners.clear();
                for (int64_t k = 0; k < n; ++k) {
                    int64_t index = 0;
                    if ((got = source.integer(property.type, &index)) != Got::Ok) return bad(element, i, got);
                    if (index < 0 || uint64_t(index) >= vertex_count) {
                        *why = source.where() + "face " + std::to_string(i) + " refers to vertex " +
                               std::to_string(index) + " but the file has " + std::to_string(vertex_count) +
                               " vertices";
                        return false;
                    }
                    corners.push_back(uint32_t(index));
                }
                for (size_t k = 1; k + 1 < corners.size(); ++k)
                    mesh->indices.insert(mesh->indices.end(), {corners[0], corners[k], corners[k + 1]});
            }
            if (is_vertex) mesh->positions[i] = glm::vec3(xyz[0], xyz[1], xyz[2]);
        }
    }
    return true;
}

}  // namespace

bool readPly(std::string_view bytes, const std::string& name, TriangleMesh* out, std::string* error) {
    bytes = withoutBom(bytes);
    Header header;
    std::string why;
    if (!parseHeader(bytes, &header, &why)) return fail(error, name, why);
    // Every count against the bytes that follow the header (all elements together), then the limits,
    // before anything is allocated. The first pass needs no layout, so an impossible count is reported
    // as such even when the header is unusable for other reasons (no face element, say); the second
    // counts each face's index list as at least 3 items, which also bounds the index memory.
    const bool ascii = header.encoding == Encoding::Ascii;
    if (!checkCounts(header, bytes.size(), nullptr, &why)) return fail(error, name, why);
    Layout layout;
    if (!findLayout(header, &layout, &why)) return fail(error, name, why);
    if (!checkCounts(header, bytes.size(), &layout, &why)) return fail(error, name, why);
    const Element& vertices = header.elements[size_t(layout.vertex)];
    const Element& faces = header.elements[size_t(layout.face)];
    if (vertices.count > kMaxMeshVertices)
        return fail(error, name,
                    headerLine(vertices.line) + "declares " + vertexLimitExceeded(vertices.count));
    if (faces.count > kMaxMeshTriangles)
        return fail(error, name,
                    headerLine(faces.line) + "declares " + std::to_string(faces.count) +
                        " faces; models are limited to " + std::to_string(kMaxMeshTriangles) +
                        " triangles (kMaxMeshTriangles)");

    TriangleMesh mesh;
    mesh.positions.resize(size_t(vertices.count));
    mesh.indices.reserve(size_t(faces.count) * 3);
    const std::string_view data = bytes.substr(header.data_offset);
    bool ok = false;
    if (ascii) {
        AsciiSource source(data, header.lines + 1);
        ok = readElements(source, header, layout, &mesh, &why);
    } else {
        BinarySource source(data, header.encoding == Encoding::BinaryBigEndian);
        ok = readElements(source, header, layout, &mesh, &why);
    }
    if (!ok) return fail(error, name, why);
    return finish(&mesh, name, out, error);
}

}  // namespace ug
