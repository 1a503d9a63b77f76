// glTF 2.0 scene export (docs/architecture.md "Files and interfaces").
//
// The JSON is built with nlohmann::json and the GLB container is assembled here, rather than through
// tinygltf's writer: a scene of ~2M instances is ~80 MB of instance attributes, and tinygltf's writer
// copies its buffer into a stream and then into a string (plus a tinygltf::Value tree for every
// extension and extras). Here the binary chunk is filled in place, once, and written next to the JSON
// with a gather write, so peak memory stays near the size of the output.
#include "io/gltf_scene_export.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <unordered_set>

#include <nlohmann/json.hpp>
#include <stb_image_write.h>

#include "core/atomic_file.h"
#include "core/hash.h"
#include "material/uv_projection.h"

namespace ug {
namespace {

// Ordered: the file lists keys in the order they are set (asset first, buffers before user content,
// which the data-URI splice below relies on).
using Json = nlohmann::ordered_json;

constexpr int kComponentUnsignedShort = 5123;
constexpr int kComponentUnsignedInt = 5125;
constexpr int kComponentFloat = 5126;
constexpr int kTargetArrayBuffer = 34962;
constexpr int kTargetElementArrayBuffer = 34963;
constexpr int kModeTriangles = 4;
constexpr int kFilterLinear = 9729;
constexpr int kFilterLinearMipmapLinear = 9987;
constexpr int kWrapRepeat = 10497;
constexpr const char* kInstancingExtension = "EXT_mesh_gpu_instancing";
constexpr const char* kTerrainName = "terrain";
// glTF forbids the largest value of the index type (primitive restart), so uint16 holds 65,535 vertices.
constexpr size_t kMaxUint16Vertices = 65535;
// GLB lengths are uint32; data URIs that large are not read by anyone either.
constexpr uint64_t kMaxBinaryBytes = uint64_t(std::numeric_limits<uint32_t>::max()) - 1024;

bool fail(std::string* error, const std::string& path, const std::string& why) {
    if (error) *error = path + ": " + why;
    return false;
}

// Z up -> Y up is the rotation C by -90 degrees about X: (x, y, z) -> (x, z, -y).
glm::vec3 toYUp(glm::vec3 v) {
    return {v.x, v.z, -v.y};
}

// An instance's world point is p + q (s v). In the file it must be C p + q' (s C v) for every v, so
// q' = C q C^-1. Conjugating a quaternion by a rotation keeps its scalar part and rotates its vector part
// by that rotation, which makes the conversion exact (no trigonometry, no rounding).
glm::quat toYUp(glm::quat q) {
    return glm::quat(q.w, q.x, q.z, -q.y);
}  // glm order: (w, x, y, z)

bool isFinite(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool isFinite(glm::quat q) {
    return std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) && std::isfinite(q.w);
}

std::string formatFloat(double v) {
    char text[32];
    std::snprintf(text, sizeof(text), "%g", v);
    return text;
}

std::string base64(const unsigned char* data, size_t size) {
    static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((size + 2) / 3 * 4);
    size_t i = 0;
    for (; i + 2 < size; i += 3) {
        const uint32_t v = uint32_t(data[i]) << 16 | uint32_t(data[i + 1]) << 8 | data[i + 2];
        out += kAlphabet[v >> 18 & 63];
        out += kAlphabet[v >> 12 & 63];
        out += kAlphabet[v >> 6 & 63];
        out += kAlphabet[v & 63];
    }
    if (i < size) {
        const bool two = i + 1 < size;
        const uint32_t v = uint32_t(data[i]) << 16 | (two ? uint32_t(data[i + 1]) << 8 : 0u);
        out += kAlphabet[v >> 18 & 63];
        out += kAlphabet[v >> 12 & 63];
        out += two ? kAlphabet[v >> 6 & 63] : '=';
        out += '=';
    }
    return out;
}

// The chunk an engine-space position falls in; false when the index does not fit an int32 (a position
// absurdly far away for the chunk size).
bool chunkOf(glm::vec3 p, double chunk_size_m, int32_t* ix, int32_t* iy) {
    const double fx = std::floor(double(p.x) / chunk_size_m), fy = std::floor(double(p.y) / chunk_size_m);
    constexpr double lo = std::numeric_limits<int32_t>::min(), hi = std::numeric_limits<int32_t>::max();
    if (!(fx >= lo && fx <= hi && fy >= lo && fy <= hi)) return false;
    *ix = int32_t(fx);
    *iy = int32_t(fy);
    return true;
}

bool validMaterial(const SurfaceMaterial& m, std::string* why) {
    for (int c = 0; c < 3; ++c)
        if (!(m.base_color[c] >= 0.0f && m.base_color[c] <= 1.0f)) {
            *why = "base_color must be in [0, 1] (got " + formatFloat(m.base_color[c]) + ")";
            return false;
        }
    if (!(m.roughness >= 0.0f && m.roughness <= 1.0f)) {
        *why = "roughness must be in [0, 1] (got " + formatFloat(m.roughness) + ")";
        return false;
    }
    if (!(m.tint_variation >= 0.0f && m.tint_variation <= 1.0f)) {
        *why = "tint_variation must be in [0, 1] (got " + formatFloat(m.tint_variation) + ")";
        return false;
    }
    if (m.texture) {
        if (!(std::isfinite(m.texture_scale_m) && m.texture_scale_m > 0.0f)) {
            *why = "texture_scale_m must be finite and > 0 (got " + formatFloat(m.texture_scale_m) + ")";
            return false;
        }
        if (!(std::abs(m.texture_rotation_deg) <= kMaxTextureRotationDeg)) {
            *why = "texture_rotation_deg must be in [-360, 360] (got " + formatFloat(m.texture_rotation_deg) + ")";
            return false;
        }
        const TextureImage& t = *m.texture;
        if (t.width < 1 || t.height < 1 || t.width > 16384 || t.height > 16384 ||
            t.rgba.size() != size_t(t.width) * size_t(t.height) * 4) {
            *why = "texture is " + std::to_string(t.width) + " x " + std::to_string(t.height) + " with " +
                   std::to_string(t.rgba.size()) + " bytes (expected 4 per pixel, sides in [1, 16384])";
            return false;
        }
    }
    return true;
}

// An instance list: finite, unit rotations, positive scales, chunk indices that fit an int32.
bool validInstances(const std::string& where, const std::vector<InstanceTransform>& instances, float chunk_size_m,
                    std::string* why) {
    for (size_t i = 0; i < instances.size(); ++i) {
        const InstanceTransform& inst = instances[i];
        const std::string at = where + " instance " + std::to_string(i) + ": ";
        if (!isFinite(inst.position) || !isFinite(inst.rotation) || !std::isfinite(inst.scale)) {
            *why = at + "non-finite position, rotation or scale";
            return false;
        }
        const float norm = glm::length(inst.rotation);
        if (std::fabs(norm - 1.0f) > 1e-3f) {
            *why = at + "rotation is not a unit quaternion (|q| = " + formatFloat(norm) + ")";
            return false;
        }
        if (!(inst.scale > 0.0f)) {
            *why = at + "scale must be > 0 (got " + formatFloat(inst.scale) + ")";
            return false;
        }
        int32_t ix = 0, iy = 0;
        if (!chunkOf(inst.position, chunk_size_m, &ix, &iy)) {
            *why = at + "position is too far from the origin for chunk_size_m " + formatFloat(chunk_size_m);
            return false;
        }
    }
    return true;
}

// Everything the caller can get wrong, checked before any allocation proportional to the scene.
bool validateScene(const SceneExport& scene, std::string* why) {
    if (!(std::isfinite(scene.chunk_size_m) && scene.chunk_size_m > 0.0f)) {
        *why = "chunk_size_m must be finite and > 0 (got " + formatFloat(scene.chunk_size_m) + ")";
        return false;
    }
    if (!std::isfinite(scene.delta_m)) {  // negative is fine: objects may interpenetrate a little
        *why = "delta_m must be finite (got " + formatFloat(scene.delta_m) + ")";
        return false;
    }
    std::unordered_set<std::string> names;
    size_t total_instances = 0;
    for (size_t t = 0; t < scene.types.size(); ++t) {
        const ExportDetailType& type = scene.types[t];
        const std::string where = "detail type " + std::to_string(t) + " '" + type.name + "'";
        if (type.name.empty()) {
            *why = "detail type " + std::to_string(t) + " has an empty name";
            return false;
        }
        if (!names.insert(type.name).second) {
            *why = where + ": duplicate type name (each type becomes one named mesh)";
            return false;
        }
        if (!type.mesh) {
            *why = where + ": mesh is null";
            return false;
        }
        std::string mesh_why;
        if (!validateMesh(*type.mesh, &mesh_why)) {
            *why = where + ": mesh: " + mesh_why;
            return false;
        }
        if (type.material && !validMaterial(*type.material, &mesh_why)) {
            *why = where + ": material: " + mesh_why;
            return false;
        }
        for (size_t s = 0; s < type.collision_spheres.size(); ++s) {
            const Sphere& sphere = type.collision_spheres[s];
            if (!isFinite(sphere.center) || !(std::isfinite(sphere.radius) && sphere.radius > 0.0f)) {
                *why = where + ": collision sphere " + std::to_string(s) +
                       " has a non-finite centre or a radius that is not finite and > 0";
                return false;
            }
        }
        if (!validInstances(where, type.instances, scene.chunk_size_m, why)) return false;
        total_instances += type.instances.size();
    }
    if (scene.terrain) {
        std::string mesh_why;
        if (!validateMesh(*scene.terrain, &mesh_why)) {
            *why = "terrain mesh: " + mesh_why;
            return false;
        }
        if (scene.terrain_material && !validMaterial(*scene.terrain_material, &mesh_why)) {
            *why = "terrain material: " + mesh_why;
            return false;
        }
        if (!names.insert(kTerrainName).second) {
            *why = std::string("the terrain's name '") + kTerrainName + "' is taken by a detail type";
            return false;
        }
    }
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const MeshInstances& entry = scene.meshes[m];
        const std::string where = "static mesh " + std::to_string(m) + " '" + entry.name + "'";
        if (entry.name.empty()) {
            *why = "static mesh " + std::to_string(m) + " has an empty name";
            return false;
        }
        if (!names.insert(entry.name).second) {
            *why = where + ": duplicate name (the detail types, the terrain and the static meshes each become one "
                           "named mesh)";
            return false;
        }
        if (!entry.mesh) {
            *why = where + ": mesh is null";
            return false;
        }
        std::string mesh_why;
        if (!validateMesh(*entry.mesh, &mesh_why)) {
            *why = where + ": mesh: " + mesh_why;
            return false;
        }
        if (entry.material && !validMaterial(*entry.material, &mesh_why)) {
            *why = where + ": material: " + mesh_why;
            return false;
        }
        if (!validInstances(where, entry.instances, scene.chunk_size_m, why)) return false;
        if (!entry.extras_json.empty()) {
            const Json extras = Json::parse(entry.extras_json, nullptr, /*allow_exceptions=*/false);
            if (!extras.is_object()) {
                *why = where + ": extras_json must be empty or a JSON object";
                return false;
            }
        }
        total_instances += entry.instances.size();
    }
    if (!scene.use_instancing_extension && total_instances > kMaxPlainNodeInstances) {
        *why = std::to_string(total_instances) + " instances are too many for one plain node each (limit " +
               std::to_string(kMaxPlainNodeInstances) + "); export with EXT_mesh_gpu_instancing instead";
        return false;
    }
    return true;
}

// The glTF document being built: JSON arrays plus the one binary buffer they point into.
class GltfBuilder {
  public:
    Json buffer_views = Json::array();
    Json accessors = Json::array();
    Json materials = Json::array();
    Json meshes = Json::array();
    Json nodes = Json::array();
    Json scene_nodes = Json::array();
    Json images = Json::array();
    Json samplers = Json::array();
    Json textures = Json::array();
    std::vector<unsigned char> bin;

    // Grows the buffer by `size` bytes (zeroed), first padding it to a multiple of 4 (every accessor
    // must be aligned to its component size; 4 covers all we write). Returns the region's offset.
    size_t grow(size_t size) {
        bin.resize((bin.size() + 3) & ~size_t(3));
        const size_t offset = bin.size();
        bin.resize(offset + size);
        return offset;
    }
    size_t append(const void* data, size_t size) {
        const size_t offset = grow(size);
        if (size) std::memcpy(bin.data() + offset, data, size);
        return offset;
    }

    int addView(size_t offset, size_t length, int target) {
        Json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}};
        if (target) view["target"] = target;
        buffer_views.push_back(std::move(view));
        return int(buffer_views.size() - 1);
    }

    int addAccessor(int view, size_t byte_offset, int component_type, size_t count, const char* type,
                    Json min = nullptr, Json max = nullptr) {
        Json acc = {{"bufferView", view}};
        if (byte_offset) acc["byteOffset"] = byte_offset;
        acc["componentType"] = component_type;
        acc["count"] = count;
        acc["type"] = type;
        if (!min.is_null()) acc["min"] = std::move(min);
        if (!max.is_null()) acc["max"] = std::move(max);
        accessors.push_back(std::move(acc));
        return int(accessors.size() - 1);
    }

    // The texture index of `image` (a PNG in its own buffer view), writing it on first use; identical
    // images (same size and bytes) share one. False when PNG encoding fails.
    bool textureOf(const TextureImage& image, int* texture) {
        const uint64_t key = hashBytes(image.rgba.data(), image.rgba.size()) ^ hashWords(uint64_t(image.width), uint64_t(image.height));
        for (const WrittenTexture& w : written_)
            if (w.key == key && w.image->width == image.width && w.image->height == image.height &&
                w.image->rgba == image.rgba) {
                *texture = w.texture;
                return true;
            }
        std::vector<unsigned char> png;
        auto sink = [](void* context, void* data, int size) {
            auto* out = static_cast<std::vector<unsigned char>*>(context);
            out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
        };
        if (!stbi_write_png_to_func(sink, &png, image.width, image.height, 4, image.rgba.data(), image.width * 4) ||
            png.empty())
            return false;
        const int view = addView(append(png.data(), png.size()), png.size(), 0);
        images.push_back({{"bufferView", view}, {"mimeType", "image/png"}});
        if (samplers.empty())
            samplers.push_back({{"magFilter", kFilterLinear},
                                {"minFilter", kFilterLinearMipmapLinear},
                                {"wrapS", kWrapRepeat},
                                {"wrapT", kWrapRepeat}});
        textures.push_back({{"sampler", 0}, {"source", int(images.size() - 1)}});
        *texture = int(textures.size() - 1);
        written_.push_back({key, &image, *texture});
        return true;
    }

    enum class UvRule { Box, PlanarXy };

    // One mesh with one triangle primitive and its own material; the mesh is engine space (Z up) and has
    // passed validateMesh, the material (optional) validMaterial. Returns the mesh index, or -1 when a
    // texture could not be encoded.
    int addMesh(const std::string& name, const TriangleMesh& input, Json extras, const SurfaceMaterial* material,
                UvRule uv_rule) {
        // Normals first, on the whole mesh, so vertices split for the uvs keep smooth normals.
        TriangleMesh with_normals;
        const TriangleMesh* source = &input;
        if (input.normals.size() != input.positions.size()) {
            with_normals.positions = input.positions;
            with_normals.indices = input.indices;
            with_normals.base_color = input.base_color;
            computeNormals(&with_normals);
            source = &with_normals;
        }
        const bool textured = material && material->texture;
        TriangleMesh split;
        std::vector<glm::vec2> uvs;
        if (textured) {
            if (uv_rule == UvRule::Box) {
                boxProjectMesh(*source, material->texture_scale_m, &split, &uvs);
                source = &split;
            } else {
                uvs.reserve(source->positions.size());
                for (const glm::vec3& p : source->positions) uvs.push_back(planarXyUv(p, material->texture_scale_m));
            }
            for (glm::vec2& uv : uvs) uv = rotateTextureUv(uv, material->texture_rotation_deg);
        }
        std::vector<glm::vec3> positions(source->positions.size()), normals(source->normals.size());
        for (size_t i = 0; i < positions.size(); ++i) positions[i] = toYUp(source->positions[i]);
        for (size_t i = 0; i < normals.size(); ++i) {
            const glm::vec3 n = source->normals[i];
            // The validator requires unit normals; a caller's zero or denormal normal gets "up".
            const float len = glm::length(n);
            normals[i] = (std::isfinite(len) && len > 1e-20f) ? toYUp(n / len) : glm::vec3(0.0f, 1.0f, 0.0f);
        }
        glm::vec3 lo = positions[0], hi = positions[0];
        for (const glm::vec3& p : positions) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        const size_t vertex_bytes = positions.size() * sizeof(glm::vec3);
        const int pos_view =
            addView(append(positions.data(), vertex_bytes), vertex_bytes, kTargetArrayBuffer);
        const int pos_acc = addAccessor(pos_view, 0, kComponentFloat, positions.size(), "VEC3",
                                        Json::array({lo.x, lo.y, lo.z}), Json::array({hi.x, hi.y, hi.z}));
        const int nrm_view = addView(append(normals.data(), vertex_bytes), vertex_bytes, kTargetArrayBuffer);
        const int nrm_acc = addAccessor(nrm_view, 0, kComponentFloat, normals.size(), "VEC3");
        int uv_acc = -1;
        if (textured) {
            const size_t bytes = uvs.size() * sizeof(glm::vec2);
            const int view = addView(append(uvs.data(), bytes), bytes, kTargetArrayBuffer);
            uv_acc = addAccessor(view, 0, kComponentFloat, uvs.size(), "VEC2");
        }

        int idx_acc = -1;
        if (positions.size() <= kMaxUint16Vertices) {
            std::vector<uint16_t> small(source->indices.begin(), source->indices.end());
            const size_t bytes = small.size() * 2;
            const int view = addView(append(small.data(), bytes), bytes, kTargetElementArrayBuffer);
            idx_acc = addAccessor(view, 0, kComponentUnsignedShort, small.size(), "SCALAR");
        } else {
            const size_t bytes = source->indices.size() * 4;
            const int view = addView(append(source->indices.data(), bytes), bytes, kTargetElementArrayBuffer);
            idx_acc = addAccessor(view, 0, kComponentUnsignedInt, source->indices.size(), "SCALAR");
        }

        if (!material) {
            const glm::vec3 color = glm::clamp(input.base_color, 0.0f, 1.0f);
            materials.push_back({{"name", name},
                                 {"pbrMetallicRoughness",
                                  {{"baseColorFactor", {color.x, color.y, color.z, 1.0f}},
                                   {"metallicFactor", 0.0},
                                   {"roughnessFactor", 0.9}}}});
        } else {
            // A textured material's texture already holds base colour x detail (sRGB), so the factor is 1.
            const glm::vec3 color = textured ? glm::vec3(1.0f) : material->base_color;
            Json pbr = {{"baseColorFactor", {color.x, color.y, color.z, 1.0f}},
                        {"metallicFactor", 0.0},
                        {"roughnessFactor", material->roughness}};
            if (textured) {
                int texture = -1;
                if (!textureOf(*material->texture, &texture)) return -1;
                pbr["baseColorTexture"] = {{"index", texture}, {"texCoord", 0}};
            }
            Json mat = {{"name", name}, {"pbrMetallicRoughness", std::move(pbr)}};
            if (material->alpha_cutout && textured) {
                mat["alphaMode"] = "MASK";
                mat["alphaCutoff"] = 0.5;
                mat["doubleSided"] = true;  // cut-out blades and leaves are seen from both sides
            }
            mat["extras"] = {{"texture", textureKindName(material->texture_kind)},
                             {"texture_scale_m", material->texture_scale_m},
                             {"tint_variation", material->tint_variation}};
            if (material->texture_rotation_deg != 0.0f)
                mat["extras"]["texture_rotation_deg"] = material->texture_rotation_deg;
            materials.push_back(std::move(mat));
        }

        Json attributes = {{"POSITION", pos_acc}, {"NORMAL", nrm_acc}};
        if (uv_acc >= 0) attributes["TEXCOORD_0"] = uv_acc;
        Json primitive = {{"attributes", std::move(attributes)},
                          {"indices", idx_acc},
                          {"material", int(materials.size() - 1)},
                          {"mode", kModeTriangles}};
        Json mesh = {{"name", name}, {"primitives", Json::array({std::move(primitive)})}};
        if (!extras.is_null()) mesh["extras"] = std::move(extras);
        meshes.push_back(std::move(mesh));
        return int(meshes.size() - 1);
    }

    int addNode(Json node) {
        nodes.push_back(std::move(node));
        return int(nodes.size() - 1);
    }

  private:
    struct WrittenTexture {
        uint64_t key;
        const TextureImage* image;  // the caller's, alive for the whole export
        int texture;
    };
    std::vector<WrittenTexture> written_;
};

// A chunk node's translation: the chunk's XY centre at engine z = 0, in Y-up file axes.
Json toYUpArray(double cx, double cy) {
    return Json::array({cx, 0.0, -cy});
}

struct ChunkedInstance {
    int32_t ix = 0;
    int32_t iy = 0;
    uint32_t index = 0;  // into the instance list
};

// The instances of one type or static mesh sorted by chunk (ix, then iy), input order within a chunk.
std::vector<ChunkedInstance> sortIntoChunks(const std::vector<InstanceTransform>& instances, double chunk_size_m) {
    std::vector<ChunkedInstance> sorted(instances.size());
    for (size_t i = 0; i < sorted.size(); ++i) {
        sorted[i].index = uint32_t(i);
        chunkOf(instances[i].position, chunk_size_m, &sorted[i].ix, &sorted[i].iy);  // checked before
    }
    std::sort(sorted.begin(), sorted.end(), [](const ChunkedInstance& a, const ChunkedInstance& b) {
        if (a.ix != b.ix) return a.ix < b.ix;
        if (a.iy != b.iy) return a.iy < b.iy;
        return a.index < b.index;
    });
    return sorted;
}

// What one instance looks like in the file, relative to its chunk node.
struct FileTransform {
    glm::vec3 translation;
    glm::quat rotation;
    float scale;
};

FileTransform fileTransform(const InstanceTransform& inst, double cx, double cy) {
    // The offset from the chunk centre is taken in double: positions far from the origin keep the
    // precision float32 still has for a value the size of one chunk.
    const glm::vec3 rel(float(double(inst.position.x) - cx), float(double(inst.position.y) - cy),
                        inst.position.z);
    return {toYUp(rel), toYUp(glm::normalize(inst.rotation)), inst.scale};
}

// The chunk nodes of `name` (a detail type or a static mesh) with EXT_mesh_gpu_instancing.
void addInstancedNodes(GltfBuilder* doc, const std::string& name, const std::vector<InstanceTransform>& instances,
                       int mesh, double chunk_size_m) {
    const size_t n = instances.size();
    if (n == 0) return;
    const std::vector<ChunkedInstance> sorted = sortIntoChunks(instances, chunk_size_m);
    // One region (and buffer view) per attribute for the whole type; each chunk's accessors are windows
    // into them. Fewer views keep the JSON small when there are thousands of chunks.
    const size_t t_off = doc->grow(n * 12), r_off = doc->grow(n * 16), s_off = doc->grow(n * 12);
    const int t_view = doc->addView(t_off, n * 12, 0);
    const int r_view = doc->addView(r_off, n * 16, 0);
    const int s_view = doc->addView(s_off, n * 12, 0);
    for (size_t begin = 0; begin < n;) {
        size_t end = begin;
        while (end < n && sorted[end].ix == sorted[begin].ix && sorted[end].iy == sorted[begin].iy) ++end;
        const int32_t ix = sorted[begin].ix, iy = sorted[begin].iy;
        const double cx = (double(ix) + 0.5) * chunk_size_m, cy = (double(iy) + 0.5) * chunk_size_m;
        for (size_t k = begin; k < end; ++k) {
            const FileTransform f = fileTransform(instances[sorted[k].index], cx, cy);
            const float t[3] = {f.translation.x, f.translation.y, f.translation.z};
            const float r[4] = {f.rotation.x, f.rotation.y, f.rotation.z, f.rotation.w};  // glTF: x, y, z, w
            const float s[3] = {f.scale, f.scale, f.scale};
            std::memcpy(doc->bin.data() + t_off + k * 12, t, 12);
            std::memcpy(doc->bin.data() + r_off + k * 16, r, 16);
            std::memcpy(doc->bin.data() + s_off + k * 12, s, 12);
        }
        const size_t count = end - begin;
        const int t_acc = doc->addAccessor(t_view, begin * 12, kComponentFloat, count, "VEC3");
        const int r_acc = doc->addAccessor(r_view, begin * 16, kComponentFloat, count, "VEC4");
        const int s_acc = doc->addAccessor(s_view, begin * 12, kComponentFloat, count, "VEC3");
        Json node = {{"name", name + "/chunk_" + std::to_string(ix) + "_" + std::to_string(iy)},
                     {"mesh", mesh},
                     {"translation", toYUpArray(cx, cy)},
                     {"extensions",
                      {{kInstancingExtension,
                        {{"attributes", {{"TRANSLATION", t_acc}, {"ROTATION", r_acc}, {"SCALE", s_acc}}}}}}}};
        doc->scene_nodes.push_back(doc->addNode(std::move(node)));
        begin = end;
    }
}

// The chunk nodes of `name` with one plain child node per instance.
void addPlainNodes(GltfBuilder* doc, const std::string& name, const std::vector<InstanceTransform>& instances,
                   int mesh, double chunk_size_m) {
    const size_t n = instances.size();
    const std::vector<ChunkedInstance> sorted = sortIntoChunks(instances, chunk_size_m);
    for (size_t begin = 0; begin < n;) {
        size_t end = begin;
        while (end < n && sorted[end].ix == sorted[begin].ix && sorted[end].iy == sorted[begin].iy) ++end;
        const int32_t ix = sorted[begin].ix, iy = sorted[begin].iy;
        const double cx = (double(ix) + 0.5) * chunk_size_m, cy = (double(iy) + 0.5) * chunk_size_m;
        Json children = Json::array();
        for (size_t k = begin; k < end; ++k) {
            const uint32_t index = sorted[k].index;
            const FileTransform f = fileTransform(instances[index], cx, cy);
            Json node = {{"name", name + "/" + std::to_string(index)},
                         {"mesh", mesh},
                         {"translation", {f.translation.x, f.translation.y, f.translation.z}},
                         {"rotation", {f.rotation.x, f.rotation.y, f.rotation.z, f.rotation.w}},
                         {"scale", {f.scale, f.scale, f.scale}}};
            children.push_back(doc->addNode(std::move(node)));
        }
        Json parent = {{"name", name + "/chunk_" + std::to_string(ix) + "_" + std::to_string(iy)},
                       {"translation", toYUpArray(cx, cy)},
                       {"children", std::move(children)}};
        doc->scene_nodes.push_back(doc->addNode(std::move(parent)));
        begin = end;
    }
}

Json meshExtras(const ExportDetailType& type, float delta_m) {
    Json spheres = Json::array();
    for (const Sphere& sphere : type.collision_spheres) {
        const glm::vec3 c = toYUp(sphere.center);
        spheres.push_back({c.x, c.y, c.z, sphere.radius});
    }
    return {{"collision_spheres", std::move(spheres)}, {"delta", delta_m}};
}

// One static mesh as the writer sees it: the terrain or a MeshInstances entry (not owned).
struct StaticEntry {
    std::string name;
    const TriangleMesh* mesh;
    const SurfaceMaterial* material;
    const std::vector<InstanceTransform>* instances;
    std::string extras_json;  // empty or a JSON object (validated)
    GltfBuilder::UvRule uv_rule;
};

// Its mesh, then its nodes: one node at the identity without instances, chunk nodes with them. False when
// its texture could not be encoded.
bool addStaticMesh(GltfBuilder* doc, const StaticEntry& entry, const SceneExport& scene, bool* instanced_nodes) {
    Json extras = entry.extras_json.empty() ? Json() : Json::parse(entry.extras_json);
    const int mesh = doc->addMesh(entry.name, *entry.mesh, std::move(extras), entry.material, entry.uv_rule);
    if (mesh < 0) return false;
    if (entry.instances->empty()) {
        doc->scene_nodes.push_back(doc->addNode({{"name", entry.name}, {"mesh", mesh}}));
    } else if (scene.use_instancing_extension) {
        addInstancedNodes(doc, entry.name, *entry.instances, mesh, scene.chunk_size_m);
        *instanced_nodes = true;
    } else {
        addPlainNodes(doc, entry.name, *entry.instances, mesh, scene.chunk_size_m);
    }
    return true;
}

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

}  // namespace

bool writeSceneGltf(const std::string& path, const SceneExport& scene, std::string* error) {
    const std::string ext = lowerExtension(path);
    if (ext != ".glb" && ext != ".gltf") return fail(error, path, "the file name must end in .glb or .gltf");
    const bool binary = ext == ".glb";

    std::string why;
    if (!validateScene(scene, &why)) return fail(error, path, why);
    Json scene_extras;
    try {
        scene_extras = Json::parse(scene.scene_extras_json);
    } catch (const Json::exception& e) {  // syntax errors and invalid UTF-8
        return fail(error, path, std::string("scene_extras_json is not valid JSON: ") + e.what());
    }
    if (!scene_extras.is_object()) return fail(error, path, "scene_extras_json must be a JSON object");

    GltfBuilder doc;
    // Reserve the buffer up front: for millions of instances, growth by doubling would briefly hold
    // twice the instance data.
    size_t estimate = 0;
    auto meshBytes = [](const TriangleMesh& m) {
        return m.positions.size() * 24 + m.indices.size() * 4 + 16;
    };
    for (const ExportDetailType& type : scene.types)
        estimate += meshBytes(*type.mesh) + type.instances.size() * 40 + 48;
    if (scene.terrain) estimate += meshBytes(*scene.terrain);
    for (const MeshInstances& entry : scene.meshes)
        estimate += meshBytes(*entry.mesh) + entry.instances.size() * 40 + 48;
    if (estimate > kMaxBinaryBytes)
        return fail(error, path,
                    "the scene needs about " + std::to_string(estimate) +
                        " bytes of binary data, over glTF's 4 GiB limit");
    doc.bin.reserve(estimate);

    bool instanced_nodes = false;
    const double chunk_size_m = scene.chunk_size_m;
    for (const ExportDetailType& type : scene.types) {
        const int mesh = doc.addMesh(type.name, *type.mesh, meshExtras(type, scene.delta_m), type.material,
                                     GltfBuilder::UvRule::Box);
        if (mesh < 0) return fail(error, path, "detail type '" + type.name + "': could not encode its texture as PNG");
        if (scene.use_instancing_extension) {
            addInstancedNodes(&doc, type.name, type.instances, mesh, chunk_size_m);
            instanced_nodes = instanced_nodes || !type.instances.empty();
        } else {
            addPlainNodes(&doc, type.name, type.instances, mesh, chunk_size_m);
        }
    }
    // The terrain is the first static mesh (one copy at the identity, its texture planar in world XY).
    std::vector<StaticEntry> statics;
    static const std::vector<InstanceTransform> kNoInstances;
    if (scene.terrain)
        statics.push_back({kTerrainName, scene.terrain, scene.terrain_material, &kNoInstances, "",
                           GltfBuilder::UvRule::PlanarXy});
    for (const MeshInstances& entry : scene.meshes)
        statics.push_back({entry.name, entry.mesh.get(), entry.material.get(), &entry.instances, entry.extras_json,
                           GltfBuilder::UvRule::Box});
    for (const StaticEntry& entry : statics) {
        if (!addStaticMesh(&doc, entry, scene, &instanced_nodes))
            return fail(error, path, "static mesh '" + entry.name + "': could not encode its texture as PNG");
    }
    doc.bin.resize((doc.bin.size() + 3) & ~size_t(3));  // the GLB BIN chunk must be 4-byte aligned
    if (doc.bin.size() > kMaxBinaryBytes)
        return fail(error, path,
                    std::to_string(doc.bin.size()) + " bytes of binary data exceed glTF's 4 GiB limit");

    // glTF forbids empty arrays, so each top-level array is written only when it has entries.
    static const std::string kUriPlaceholder = "ug-buffer-data-uri-placeholder";
    Json root;
    root["asset"] = {{"version", "2.0"}, {"generator", "Undergrowth"}};
    // Used, not required: a viewer without the extension still loads the file (one copy per chunk).
    if (instanced_nodes) root["extensionsUsed"] = Json::array({kInstancingExtension});
    if (!doc.bin.empty()) {
        Json buffer = {{"byteLength", doc.bin.size()}};
        if (!binary) buffer["uri"] = kUriPlaceholder;
        root["buffers"] = Json::array({std::move(buffer)});
    }
    if (!doc.buffer_views.empty()) root["bufferViews"] = std::move(doc.buffer_views);
    if (!doc.accessors.empty()) root["accessors"] = std::move(doc.accessors);
    if (!doc.materials.empty()) root["materials"] = std::move(doc.materials);
    if (!doc.textures.empty()) {
        root["textures"] = std::move(doc.textures);
        root["images"] = std::move(doc.images);
        root["samplers"] = std::move(doc.samplers);
    }
    if (!doc.meshes.empty()) root["meshes"] = std::move(doc.meshes);
    if (!doc.nodes.empty()) root["nodes"] = std::move(doc.nodes);
    Json gltf_scene = {{"name", "Undergrowth"}};
    if (!doc.scene_nodes.empty()) gltf_scene["nodes"] = std::move(doc.scene_nodes);
    gltf_scene["extras"] = std::move(scene_extras);
    root["scene"] = 0;
    root["scenes"] = Json::array({std::move(gltf_scene)});

    // Names come from the caller: invalid UTF-8 is replaced (U+FFFD) rather than thrown on.
    std::string text = root.dump(-1, ' ', false, Json::error_handler_t::replace);
    root = Json();  // the JSON tree of a large scene is sizeable: free it before the output is assembled

    if (binary) {
        text.resize((text.size() + 3) & ~size_t(3), ' ');  // the JSON chunk is padded with spaces
        const uint64_t total = 12 + 8 + text.size() + (doc.bin.empty() ? 0 : 8 + doc.bin.size());
        if (total > std::numeric_limits<uint32_t>::max())
            return fail(error, path,
                        "the file would be " + std::to_string(total) + " bytes, over the GLB limit");
        const uint32_t header[3] = {0x46546C67u /* "glTF" */, 2u, uint32_t(total)};
        const uint32_t json_head[2] = {uint32_t(text.size()), 0x4E4F534Au /* "JSON" */};
        const uint32_t bin_head[2] = {uint32_t(doc.bin.size()), 0x004E4942u /* "BIN\0" */};
        std::vector<ByteSpan> parts = {
            {header, sizeof(header)}, {json_head, sizeof(json_head)}, {text.data(), text.size()}};
        if (!doc.bin.empty()) {
            parts.push_back({bin_head, sizeof(bin_head)});
            parts.push_back({doc.bin.data(), doc.bin.size()});
        }
        return writeFileAtomically(path, parts, error);
    }

    if (doc.bin.empty()) return writeTextFileAtomically(path, text, error);
    // Splice the data URI into the dumped text instead of storing it in the JSON tree, which would copy
    // the base64 text (4/3 of the binary size) twice more. "buffers" is written before any name or extras
    // a caller controls, so the first occurrence of the placeholder is ours.
    const std::string quoted = "\"" + kUriPlaceholder + "\"";
    const size_t at = text.find(quoted);
    if (at == std::string::npos) return fail(error, path, "internal error: buffer URI placeholder missing");
    const std::string encoded = base64(doc.bin.data(), doc.bin.size());
    doc.bin = {};
    static const std::string kPrefix = "\"data:application/octet-stream;base64,";
    static const std::string kSuffix = "\"";
    const std::vector<ByteSpan> parts = {
        {text.data(), at},
        {kPrefix.data(), kPrefix.size()},
        {encoded.data(), encoded.size()},
        {kSuffix.data(), kSuffix.size()},
        {text.data() + at + quoted.size(), text.size() - at - quoted.size()}};
    return writeFileAtomically(path, parts, error);
}

}  // namespace ug
