// glTF mesh IO on top of tinygltf. tinygltf parses the JSON and the GLB container; everything that
// reads buffer bytes (accessors, views, strides) is re-checked here, because a truncated or hostile
// file must give an error, never an out-of-bounds read. What tinygltf itself may allocate is bounded
// before it runs: the file's size is checked first, external buffers are read through our own
// size-capped callback, and images are not decoded (a small PNG can declare gigapixels; a mesh load
// needs no pixels).
#include "io/gltf_mesh_io.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <exception>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <limits>
#include <sstream>

#include "core/atomic_file.h"
#include "mesh/mesh_readers.h"

namespace ug {
namespace {

namespace fs = std::filesystem;

bool fail(std::string* error, const std::string& path, const std::string& why) {
    if (error) *error = path + ": " + why;
    return false;
}

// Byte span of one accessor's elements inside its buffer, checked against the view and the buffer.
struct AccessorSpan {
    const unsigned char* data = nullptr;
    size_t stride = 0;
    size_t count = 0;
};

bool accessorSpan(const tinygltf::Model& model, int accessor_index, size_t element_size, AccessorSpan* span,
                  std::string* why) {
    if (accessor_index < 0 || size_t(accessor_index) >= model.accessors.size()) {
        *why = "accessor " + std::to_string(accessor_index) + " does not exist";
        return false;
    }
    const tinygltf::Accessor& acc = model.accessors[size_t(accessor_index)];
    const std::string where = "accessor " + std::to_string(accessor_index);
    if (acc.sparse.isSparse) {
        *why = where + " is sparse (not supported)";
        return false;
    }
    if (acc.bufferView < 0 || size_t(acc.bufferView) >= model.bufferViews.size()) {
        *why = where + " has no valid bufferView";
        return false;
    }
    const tinygltf::BufferView& view = model.bufferViews[size_t(acc.bufferView)];
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size()) {
        *why = where + ": bufferView " + std::to_string(acc.bufferView) + " has no valid buffer";
        return false;
    }
    const std::vector<unsigned char>& bytes = model.buffers[size_t(view.buffer)].data;
    const size_t stride = view.byteStride ? view.byteStride : element_size;
    if (stride < element_size) {
        *why = where + ": byteStride " + std::to_string(stride) + " is smaller than the element";
        return false;
    }
    // Every field is a size_t straight from the JSON, so each test is written as a subtraction from a
    // bound already known to hold: no sum or product here can wrap around.
    if (view.byteOffset > bytes.size() || view.byteLength > bytes.size() - view.byteOffset) {
        *why = where + ": bufferView " + std::to_string(acc.bufferView) + " (offset " +
               std::to_string(view.byteOffset) + ", length " + std::to_string(view.byteLength) +
               ") overruns its " + std::to_string(bytes.size()) + "-byte buffer";
        return false;
    }
    if (acc.count > 0) {
        const bool fits = acc.byteOffset <= view.byteLength &&
                          element_size <= view.byteLength - acc.byteOffset &&
                          acc.count - 1 <= (view.byteLength - acc.byteOffset - element_size) / stride;
        if (!fits) {
            *why = where + ": " + std::to_string(acc.count) + " elements overrun bufferView " +
                   std::to_string(acc.bufferView);
            return false;
        }
        span->data = bytes.data() + view.byteOffset + acc.byteOffset;
    }
    span->stride = stride;
    span->count = acc.count;
    return true;
}

glm::mat4 nodeLocalMatrix(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) {
        glm::mat4 m;
        for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = float(node.matrix[size_t(i)]);  // column-major
        return m;
    }
    glm::mat4 m(1.0f);
    if (node.translation.size() == 3)
        m = glm::translate(
            m, glm::vec3(float(node.translation[0]), float(node.translation[1]), float(node.translation[2])));
    if (node.rotation.size() == 4) {
        // glTF stores (x, y, z, w); glm's constructor takes (w, x, y, z).
        const glm::quat q(float(node.rotation[3]), float(node.rotation[0]), float(node.rotation[1]),
                          float(node.rotation[2]));
        m = m * glm::mat4_cast(q);
    }
    if (node.scale.size() == 3)
        m = glm::scale(m, glm::vec3(float(node.scale[0]), float(node.scale[1]), float(node.scale[2])));
    return m;
}

struct GltfReader {
    const tinygltf::Model& model;
    TriangleMesh mesh;
    bool have_color = false;
    std::string why;
    std::vector<char> visited;  // per node, sized on first use

    // `node_index` < 0: the primitive is taken untransformed (a file without scenes).
    bool addPrimitive(const tinygltf::Primitive& prim, const glm::mat4& xf, int mesh_index, size_t prim_index,
                      int node_index) {
        const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
        if (mode != TINYGLTF_MODE_TRIANGLES) return true;  // points, lines and strips are skipped
        const std::string where =
            "mesh " + std::to_string(mesh_index) + " primitive " + std::to_string(prim_index);
        auto pos_it = prim.attributes.find("POSITION");
        if (pos_it == prim.attributes.end()) {
            why = where + ": triangle primitive without POSITION";
            return false;
        }
        const int pos_acc = pos_it->second;
        if (pos_acc < 0 || size_t(pos_acc) >= model.accessors.size()) {
            why = where + ": POSITION accessor " + std::to_string(pos_acc) + " does not exist";
            return false;
        }
        const tinygltf::Accessor& pacc = model.accessors[size_t(pos_acc)];
        if (pacc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || pacc.type != TINYGLTF_TYPE_VEC3) {
            why = where + ": POSITION accessor " + std::to_string(pos_acc) + " is not float VEC3";
            return false;
        }
        AccessorSpan pspan;
        if (!accessorSpan(model, pos_acc, 12, &pspan, &why)) return false;
        // Totals, not per primitive: many nodes may instance one large mesh.
        if (pspan.count > kMaxMeshVertices - mesh.positions.size()) {
            why = where + ": more than " + std::to_string(kMaxMeshVertices) +
                  " vertices in the model (kMaxMeshVertices)";
            return false;
        }
        // note: no reserve here; an exact reserve per instance would make many instances quadratic.
        const size_t base = mesh.positions.size();
        for (size_t i = 0; i < pspan.count; ++i) {
            float v[3];
            std::memcpy(v, pspan.data + i * pspan.stride, 12);
            for (int k = 0; k < 3; ++k)
                if (!std::isfinite(v[k])) {
                    why = where + ": POSITION vertex " + std::to_string(i) + " has a non-finite " +
                          std::string(1, "xyz"[k]) + " coordinate (" + (std::isnan(v[k]) ? "nan" : "inf") +
                          ")";
                    return false;
                }
            const glm::vec4 p = xf * glm::vec4(v[0], v[1], v[2], 1.0f);
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
                why = where + ": POSITION vertex " + std::to_string(i) +
                      " is not finite after the transform of node " + std::to_string(node_index);
                return false;
            }
            mesh.positions.emplace_back(p.x, p.y, p.z);
        }
        if (prim.indices >= 0) {
            if (size_t(prim.indices) >= model.accessors.size()) {
                why = where + ": index accessor " + std::to_string(prim.indices) + " does not exist";
                return false;
            }
            const tinygltf::Accessor& iacc = model.accessors[size_t(prim.indices)];
            size_t size = 0;
            switch (iacc.componentType) {
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
                    size = 1;
                    break;
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
                    size = 2;
                    break;
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
                    size = 4;
                    break;
                default:
                    why = where + ": index accessor " + std::to_string(prim.indices) +
                          " has component type " + std::to_string(iacc.componentType) +
                          " (want ubyte, ushort or uint)";
                    return false;
            }
            if (iacc.type != TINYGLTF_TYPE_SCALAR) {
                why = where + ": index accessor " + std::to_string(prim.indices) + " is not SCALAR";
                return false;
            }
            AccessorSpan ispan;
            if (!accessorSpan(model, prim.indices, size, &ispan, &why)) return false;
            if (ispan.count % 3 != 0) {
                why = where + ": index accessor " + std::to_string(prim.indices) + " has " +
                      std::to_string(ispan.count) + " indices, not a multiple of 3";
                return false;
            }
            if (!triangleRoom(ispan.count / 3, where)) return false;
            for (size_t i = 0; i < ispan.count; ++i) {
                const unsigned char* p = ispan.data + i * ispan.stride;
                uint32_t index = 0;
                if (size == 1)
                    index = p[0];
                else if (size == 2) {
                    uint16_t s;
                    std::memcpy(&s, p, 2);
                    index = s;
                } else
                    std::memcpy(&index, p, 4);
                if (index >= pspan.count) {
                    why = where + ": index " + std::to_string(i) + " is " + std::to_string(index) + " but " +
                          "POSITION has " + std::to_string(pspan.count) + " vertices";
                    return false;
                }
                mesh.indices.push_back(uint32_t(base) + index);
            }
        } else {
            if (pspan.count % 3 != 0) {
                why = where + ": non-indexed POSITION has " + std::to_string(pspan.count) +
                      " vertices, not a multiple of 3";
                return false;
            }
            if (!triangleRoom(pspan.count / 3, where)) return false;
            for (size_t i = 0; i + 2 < pspan.count; i += 3)
                for (size_t k = 0; k < 3; ++k) mesh.indices.push_back(uint32_t(base + i + k));
        }
        if (!have_color && prim.material >= 0 && size_t(prim.material) < model.materials.size()) {
            const std::vector<double>& f =
                model.materials[size_t(prim.material)].pbrMetallicRoughness.baseColorFactor;
            if (f.size() >= 3) {
                mesh.base_color = glm::clamp(glm::vec3(float(f[0]), float(f[1]), float(f[2])), 0.0f, 1.0f);
                have_color = true;
            }
        }
        return true;
    }

    bool triangleRoom(size_t triangles, const std::string& where) {
        if (triangles <= kMaxMeshTriangles - mesh.triangleCount()) return true;
        why = where + ": more than " + std::to_string(kMaxMeshTriangles) +
              " triangles in the model (kMaxMeshTriangles)";
        return false;
    }

    bool addNode(int node_index, const glm::mat4& parent, int depth) {
        if (node_index < 0 || size_t(node_index) >= model.nodes.size()) {
            why = "node " + std::to_string(node_index) + " does not exist";
            return false;
        }
        // glTF nodes form disjoint trees. A node reached twice would let a tiny file that lists the same
        // child many times at every level make the walk exponential, so it is an error.
        if (visited.empty()) visited.assign(model.nodes.size(), 0);
        if (visited[size_t(node_index)]) {
            why = "node " + std::to_string(node_index) + " is reached twice (glTF nodes must form trees)";
            return false;
        }
        visited[size_t(node_index)] = 1;
        // glTF forbids cycles; a depth cap turns a cyclic (hostile) file into an error, not a stack overflow.
        if (depth > 64) {
            why = "node hierarchy deeper than 64 (cycle?) at node " + std::to_string(node_index);
            return false;
        }
        const tinygltf::Node& node = model.nodes[size_t(node_index)];
        const glm::mat4 xf = parent * nodeLocalMatrix(node);
        if (node.mesh >= 0) {
            if (size_t(node.mesh) >= model.meshes.size()) {
                why = "node " + std::to_string(node_index) + " references missing mesh " +
                      std::to_string(node.mesh);
                return false;
            }
            const std::vector<tinygltf::Primitive>& prims = model.meshes[size_t(node.mesh)].primitives;
            for (size_t p = 0; p < prims.size(); ++p)
                if (!addPrimitive(prims[p], xf, node.mesh, p, node_index)) return false;
        }
        for (int child : node.children)
            if (!addNode(child, xf, depth + 1)) return false;
        return true;
    }
};

// tinygltf's file callback for external buffers and images: the same size cap as the model file, and
// one budget for all of them together (a .gltf may name the same large file many times).
struct ExternalBudget {
    uint64_t left = kMaxMeshFileBytes;
};

bool readExternalFile(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                      void* user) {
    ExternalBudget* budget = static_cast<ExternalBudget*>(user);
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) {
        if (err) *err += "not a regular file";
        return false;
    }
    const uintmax_t size = fs::file_size(path, ec);
    if (ec) {
        if (err) *err += "cannot read its size: " + ec.message();
        return false;
    }
    if (size > budget->left) {
        if (err)
            *err += std::to_string(size) + " bytes would take the model past " +
                    std::to_string(kMaxMeshFileBytes) + " bytes with its external files (kMaxMeshFileBytes)";
        return false;
    }
    std::string why;
    if (!readWholeFile(path, out, &why, size_t(budget->left))) {
        if (err) *err += why;
        return false;
    }
    budget->left -= out->size();
    return true;
}

// Images are never needed to load a mesh; skipping the decode also skips its allocation.
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int,
               void*) {
    return true;
}

// The GLB container (glTF 2.0 §4.4), checked before tinygltf reads it: tinygltf bounds the BIN chunk's
// data without its 8-byte chunk header, so a BIN length that reaches the file's end makes it read up to 8
// bytes past the buffer. Header: magic, version 2, total length within the file; chunk 0 JSON, then an
// optional chunk 1 BIN, each wholly inside the declared length.
bool checkGlbContainer(const std::vector<unsigned char>& bytes, std::string* why) {
    auto u32 = [&](size_t at) {
        return uint32_t(bytes[at]) | uint32_t(bytes[at + 1]) << 8 | uint32_t(bytes[at + 2]) << 16 |
               uint32_t(bytes[at + 3]) << 24;
    };
    if (bytes.size() < 20) return (*why = "GLB shorter than its 20-byte header and first chunk header", false);
    if (u32(4) != 2) return (*why = "GLB version " + std::to_string(u32(4)) + " (only 2 is read)", false);
    const uint64_t length = u32(8);
    if (length > bytes.size())
        return (*why = "GLB header declares " + std::to_string(length) + " bytes, the file has " +
                       std::to_string(bytes.size()),
                false);
    const uint64_t json_end = 20 + uint64_t(u32(12));
    if (u32(16) != 0x4E4F534Au || json_end > length)
        return (*why = "GLB's first chunk is not a JSON chunk inside the file", false);
    if (json_end == length) return true;  // no BIN chunk
    if (json_end + 8 > length) return (*why = "GLB has a truncated chunk header after the JSON chunk", false);
    const uint64_t bin_end = json_end + 8 + uint64_t(u32(size_t(json_end)));
    if (u32(size_t(json_end) + 4) == 0x004E4942u && bin_end > length)
        return (*why = "GLB's BIN chunk declares " + std::to_string(u32(size_t(json_end))) +
                       " bytes, more than the file holds after its header",
                false);
    return true;
}

}  // namespace

bool loadGltfMesh(const std::string& path, TriangleMesh* out, std::string* error) {
    // The size is checked before anything is read, so tinygltf never sees more than kMaxMeshFileBytes
    // (which also keeps the length within tinygltf's unsigned int).
    std::vector<unsigned char> bytes;
    if (!readMeshFileBytes(path, &bytes, error)) return false;
    static_assert(kMaxMeshFileBytes <= std::numeric_limits<unsigned int>::max());

    tinygltf::TinyGLTF loader;
    ExternalBudget budget;
    budget.left -= bytes.size();
    tinygltf::FsCallbacks callbacks{&tinygltf::FileExists, &tinygltf::ExpandFilePath, &readExternalFile,
                                    &tinygltf::WriteWholeFile, &budget};
    loader.SetFsCallbacks(callbacks);
    loader.SetImageLoader(&skipImage, nullptr);
    tinygltf::Model model;
    std::string err, warn;
    const std::string base_dir = fs::path(path).parent_path().string();
    const bool is_glb = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
    bool ok = false;
    if (!is_glb && fs::path(path).extension() == ".glb")
        return fail(error, path, "not a binary glTF (the file does not start with \"glTF\")");
    std::string container_error;
    if (is_glb && !checkGlbContainer(bytes, &container_error)) return fail(error, path, container_error);
    // tinygltf reports most problems in `err`, but some malformed files reach a throwing call inside it
    // (a zero-byte buffer's data.at(0)); no exception may leave a reader.
    try {
        if (is_glb) {
            ok = loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), unsigned(bytes.size()), base_dir);
        } else {
            const std::string text(bytes.begin(), bytes.end());
            ok = loader.LoadASCIIFromString(&model, &err, &warn, text.c_str(), unsigned(text.size()), base_dir);
        }
    } catch (const std::exception& e) {
        ok = false;
        err = std::string("malformed file (") + e.what() + ")";
    }
    if (!ok) {
        while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
        return fail(error, path, "glTF parse error: " + (err.empty() ? std::string("unknown") : err));
    }

    GltfReader reader{model, {}, false, {}, {}};
    bool walked = true;
    if (!model.scenes.empty()) {
        const int scene = (model.defaultScene >= 0 && size_t(model.defaultScene) < model.scenes.size())
                              ? model.defaultScene
                              : 0;
        for (int node : model.scenes[size_t(scene)].nodes)
            if (!(walked = reader.addNode(node, glm::mat4(1.0f), 0))) break;
    } else {
        // note: a file without scenes is legal ("a library of meshes"); take every mesh untransformed.
        for (size_t m = 0; m < model.meshes.size() && walked; ++m)
            for (size_t p = 0; p < model.meshes[m].primitives.size() && walked; ++p)
                walked = reader.addPrimitive(model.meshes[m].primitives[p], glm::mat4(1.0f), int(m), p, -1);
    }
    if (!walked) return fail(error, path, reader.why);
    if (reader.mesh.indices.empty()) return fail(error, path, "no triangles");
    // validateMesh is the backstop; the walk above already named any bad element.
    std::string why;
    if (!validateMesh(reader.mesh, &why)) return fail(error, path, why);
    computeNormals(&reader.mesh);
    *out = std::move(reader.mesh);
    return true;
}

bool writeGltfMeshes(const std::string& path,
                     const std::vector<std::pair<std::string, const TriangleMesh*>>& meshes,
                     std::string* error) {
    if (meshes.empty()) return fail(error, path, "nothing to write (no meshes)");
    for (size_t m = 0; m < meshes.size(); ++m) {
        std::string why;
        assert(meshes[m].second);
        if (!validateMesh(*meshes[m].second, &why))
            return fail(error, path, "mesh " + std::to_string(m) + " (" + meshes[m].first + "): " + why);
    }

    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "Undergrowth";
    model.buffers.emplace_back();
    std::vector<unsigned char>& buffer = model.buffers[0].data;
    model.scenes.emplace_back();
    model.defaultScene = 0;

    auto addView = [&](const void* data, size_t size, int target) {
        while (buffer.size() % 4) buffer.push_back(0);
        tinygltf::BufferView view;
        view.buffer = 0;
        view.byteOffset = buffer.size();
        view.byteLength = size;
        view.target = target;
        const unsigned char* p = static_cast<const unsigned char*>(data);
        buffer.insert(buffer.end(), p, p + size);
        model.bufferViews.push_back(view);
        return int(model.bufferViews.size() - 1);
    };
    auto addVec3Accessor = [&](const std::vector<glm::vec3>& values) {
        tinygltf::Accessor acc;
        acc.bufferView =
            addView(values.data(), values.size() * sizeof(glm::vec3), TINYGLTF_TARGET_ARRAY_BUFFER);
        acc.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
        acc.type = TINYGLTF_TYPE_VEC3;
        acc.count = values.size();
        glm::vec3 lo = values[0], hi = values[0];
        for (const glm::vec3& v : values) {
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
        acc.minValues = {lo.x, lo.y, lo.z};
        acc.maxValues = {hi.x, hi.y, hi.z};
        model.accessors.push_back(acc);
        return int(model.accessors.size() - 1);
    };

    for (const auto& [name, source] : meshes) {
        TriangleMesh mesh = *source;
        if (mesh.normals.size() != mesh.positions.size()) computeNormals(&mesh);
        convertZUpToYUp(&mesh);

        tinygltf::Material material;
        material.name = name;
        material.pbrMetallicRoughness.baseColorFactor = {mesh.base_color.x, mesh.base_color.y,
                                                         mesh.base_color.z, 1.0};
        material.pbrMetallicRoughness.metallicFactor = 0.0;
        material.pbrMetallicRoughness.roughnessFactor = 0.9;
        material.doubleSided = false;
        model.materials.push_back(material);

        tinygltf::Primitive prim;
        prim.mode = TINYGLTF_MODE_TRIANGLES;
        prim.material = int(model.materials.size() - 1);
        prim.attributes["POSITION"] = addVec3Accessor(mesh.positions);
        prim.attributes["NORMAL"] = addVec3Accessor(mesh.normals);
        tinygltf::Accessor iacc;
        iacc.bufferView =
            addView(mesh.indices.data(), mesh.indices.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
        iacc.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
        iacc.type = TINYGLTF_TYPE_SCALAR;
        iacc.count = mesh.indices.size();
        uint32_t lo = mesh.indices[0], hi = mesh.indices[0];
        for (uint32_t i : mesh.indices) {
            lo = std::min(lo, i);
            hi = std::max(hi, i);
        }
        iacc.minValues = {double(lo)};
        iacc.maxValues = {double(hi)};
        model.accessors.push_back(iacc);
        prim.indices = int(model.accessors.size() - 1);

        tinygltf::Mesh gmesh;
        gmesh.name = name;
        gmesh.primitives.push_back(prim);
        model.meshes.push_back(gmesh);
        tinygltf::Node node;
        node.name = name;
        node.mesh = int(model.meshes.size() - 1);
        model.nodes.push_back(node);
        model.scenes[0].nodes.push_back(int(model.nodes.size() - 1));
    }
    while (buffer.size() % 4) buffer.push_back(0);

    const fs::path target(path);
    const bool binary = target.extension() == ".glb";
    std::ostringstream stream;
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&model, stream, /*prettyPrint=*/!binary, binary))
        return fail(error, path, "tinygltf could not serialize the model");
    const std::string data = stream.str();

    // Atomic replace (unique temporary file, fsync, rename): readers see the old file or the new one.
    return writeFileAtomically(path, data.data(), data.size(), error);
}

bool writeModelFolder(const std::string& dir, const std::vector<std::string>& names,
                      const std::function<void(const std::string& name, TriangleMesh* mesh)>& make,
                      std::string* error) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) {
        if (error) *error = dir + ": cannot create the folder: " + ec.message();
        return false;
    }
    for (const std::string& name : names) {
        TriangleMesh mesh;
        make(name, &mesh);
        const std::string path = (std::filesystem::path(dir) / (name + ".glb")).string();
        if (!writeGltfMeshes(path, {{name, &mesh}}, error)) return false;
    }
    return true;
}

}  // namespace ug
