// Detail models: mesh + collision spheres + anchors (Ghost Tile §4.1 anchors, §4.3 sphere sets).
// Anchors "can be also generated procedurally by sampling the volume or the surface of the objects"
// (§4.1); the union of spheres "lends itself for the automatic generation of anchor points" (§4.3),
// hence AnchorMode::SphereCenters as the default.
#include "mesh/detail_model.h"

#include <limits>

#include <cmath>

#include "core/hash.h"
#include "mesh/mesh_loader.h"

namespace ug {
namespace {

constexpr uint64_t kAnchorSeedSalt = 0xa9c4'0125ull;

bool isFinite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string label(const DetailModelSource& source) {
    std::string s = "detail model '" + source.name + "'";
    if (!source.mesh_path.empty()) s += " (" + source.mesh_path + ")";
    return s;
}

bool fail(std::string* error, const DetailModelSource& source, const std::string& why) {
    if (error) *error = label(source) + ": " + why;
    return false;
}

bool checkSource(const DetailModelSource& source, std::string* error) {
    if (!(std::isfinite(source.scale) && source.scale > 0.0f))
        return fail(error, source, "scale = " + std::to_string(source.scale) + " must be finite and > 0");
    // The fit's limits (surface_samples above all) are refused here, before the mesh file is read.
    std::string why;
    if (!validateSphereFitSettings(source.fit, &why)) return fail(error, source, why);
    for (size_t i = 0; i < source.authored_spheres.size(); ++i) {
        const Sphere& s = source.authored_spheres[i];
        if (!(std::isfinite(s.radius) && s.radius > 0.0f) || !isFinite(s.center))
            return fail(error, source, "authored_spheres[" + std::to_string(i) + "] has radius " +
                                           std::to_string(s.radius) + " (want finite > 0) or a non-finite centre");
    }
    switch (source.anchor_mode) {
        case AnchorMode::Authored:
            if (source.authored_anchors.empty())
                return fail(error, source, "anchor_mode Authored but authored_anchors is empty");
            for (size_t i = 0; i < source.authored_anchors.size(); ++i)
                if (!isFinite(source.authored_anchors[i]))
                    return fail(error, source, "authored_anchors[" + std::to_string(i) + "] is not finite");
            break;
        case AnchorMode::Surface:
        case AnchorMode::SphereCenters:
            if (source.anchor_count == 0 || source.anchor_count > 4096)
                return fail(error, source, "anchor_count = " + std::to_string(source.anchor_count) +
                                               " is outside [1, 4096]");
            break;
        case AnchorMode::Center:
            break;
        default:
            return fail(error, source, "anchor_mode " + std::to_string(int(source.anchor_mode)) + " is unknown");
    }
    return true;
}

// The mesh is in engine space (metres, Z up) here.
bool buildModel(const DetailModelSource& source, TriangleMesh mesh, DetailModel* out, std::string* error) {
    std::string why;
    if (!validateMesh(mesh, &why)) return fail(error, source, why);
    if (mesh.normals.size() != mesh.positions.size()) computeNormals(&mesh);

    DetailModel model;
    model.name = source.name;
    if (!source.authored_spheres.empty()) {
        model.spheres = source.authored_spheres;
    } else if (!fitSphereSet(mesh, source.fit, &model.spheres, &model.fit_report, &why)) {
        return fail(error, source, why);
    }

    switch (source.anchor_mode) {
        case AnchorMode::Authored: model.anchors = source.authored_anchors; break;
        case AnchorMode::Center: model.anchors = {glm::vec3(0.0f)}; break;
        case AnchorMode::SphereCenters: {
            // Farthest-point thinning to anchor_count centres: evaluating the density at ~90 anchors per
            // candidate would dominate instantiation, and 8 well-spread ones bound the object as well.
            // The first is the centre nearest the origin: the instantiator tests it first.
            std::vector<glm::vec3> centres;
            for (const Sphere& sp : model.spheres) centres.push_back(sp.center);
            std::vector<float> gap(centres.size(), std::numeric_limits<float>::infinity());
            size_t next = 0;
            for (size_t k = 1; k < centres.size(); ++k)
                if (glm::length(centres[k]) < glm::length(centres[next])) next = k;
            while (model.anchors.size() < std::min<size_t>(source.anchor_count, centres.size())) {
                model.anchors.push_back(centres[next]);
                size_t far = 0;
                for (size_t k = 0; k < centres.size(); ++k) {
                    gap[k] = std::min(gap[k], glm::length(centres[k] - centres[next]));
                    if (gap[k] > gap[far]) far = k;
                }
                next = far;
            }
            break;
        }
        case AnchorMode::Surface:
            sampleSurface(mesh, source.anchor_count, hashWords(source.fit.seed, kAnchorSeedSalt), &model.anchors, nullptr);
            model.anchors.push_back(glm::vec3(0.0f));
            break;
    }
    if (model.anchors.empty()) model.anchors.push_back(glm::vec3(0.0f));

    // Bounds: centre of the box around spheres and vertices, radius reaching the farthest of both.
    glm::vec3 lo = model.spheres[0].center - model.spheres[0].radius, hi = model.spheres[0].center + model.spheres[0].radius;
    for (const Sphere& s : model.spheres) {
        lo = glm::min(lo, s.center - s.radius);
        hi = glm::max(hi, s.center + s.radius);
    }
    const Bounds3 mesh_box = meshBounds(mesh);
    lo = glm::min(lo, mesh_box.min);
    hi = glm::max(hi, mesh_box.max);
    model.bounds.center = 0.5f * (lo + hi);
    float radius = 0.0f;
    for (const Sphere& s : model.spheres) radius = std::max(radius, glm::length(s.center - model.bounds.center) + s.radius);
    for (const glm::vec3& p : mesh.positions) radius = std::max(radius, glm::length(p - model.bounds.center));
    model.bounds.radius = radius * (1.0f + 1e-6f);  // float rounding must not leave a sphere poking out
    model.mesh = std::move(mesh);
    *out = std::move(model);
    return true;
}

}  // namespace

bool loadDetailModel(const DetailModelSource& source, DetailModel* out, std::string* error) {
    if (!checkSource(source, error)) return false;
    TriangleMesh mesh;
    std::string why;
    if (!loadMeshFile(source.mesh_path, &mesh, &why)) return fail(error, source, why);
    if (source.y_up) convertYUpToZUp(&mesh);
    if (source.scale != 1.0f) scaleMesh(&mesh, source.scale);
    return buildModel(source, std::move(mesh), out, error);
}

bool makeDetailModel(const DetailModelSource& source, TriangleMesh mesh, DetailModel* out, std::string* error) {
    if (!checkSource(source, error)) return false;
    if (source.scale != 1.0f) scaleMesh(&mesh, source.scale);
    return buildModel(source, std::move(mesh), out, error);
}

}  // namespace ug
