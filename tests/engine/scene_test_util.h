// Helpers for the scene tests: bitwise comparison of density fields (structure and values), and a
// temporary folder removed with everything in it.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>

#include "field/density_field.h"

namespace ug::test {

// A fresh folder under the system's temporary directory (`prefix` + random digits), removed at the end.
class TempDir {
public:
    explicit TempDir(const std::string& prefix) {
        std::random_device rd;
        path_ = std::filesystem::temp_directory_path() / (prefix + std::to_string(rd()) + std::to_string(rd()));
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

inline bool sameBits(float a, float b) {
    return std::memcmp(&a, &b, sizeof(float)) == 0;
}
inline bool sameBits(glm::vec3 a, glm::vec3 b) {
    return sameBits(a.x, b.x) && sameBits(a.y, b.y) && sameBits(a.z, b.z);
}

// Every member a primitive's kind uses, bit for bit (also the unused ones: the builders set them the same
// way).
inline ::testing::AssertionResult samePrimitive(const Primitive& a, const Primitive& b) {
    if (a.kind != b.kind)
        return ::testing::AssertionFailure() << "kind " << int(a.kind) << " vs " << int(b.kind);
    if (!sameBits(a.weight, b.weight)) return ::testing::AssertionFailure() << "weight";
    if (!sameBits(a.radius_m, b.radius_m)) return ::testing::AssertionFailure() << "radius_m";
    if (!sameBits(a.center_m, b.center_m)) return ::testing::AssertionFailure() << "center_m";
    if (!sameBits(a.end_m, b.end_m)) return ::testing::AssertionFailure() << "end_m";
    if (!sameBits(a.end_radius_m, b.end_radius_m)) return ::testing::AssertionFailure() << "end_radius_m";
    if (!sameBits(a.normal, b.normal)) return ::testing::AssertionFailure() << "normal";
    if (!sameBits(a.disc_radius_m, b.disc_radius_m)) return ::testing::AssertionFailure() << "disc_radius_m";
    if (!sameBits(a.half_extents_m, b.half_extents_m))
        return ::testing::AssertionFailure() << "half_extents_m";
    if (!sameBits(a.thickness_m, b.thickness_m)) return ::testing::AssertionFailure() << "thickness_m";
    if (a.height_field != b.height_field) return ::testing::AssertionFailure() << "height_field";
    if (a.stroke != b.stroke) return ::testing::AssertionFailure() << "stroke " << a.stroke << " vs " << b.stroke;
    return ::testing::AssertionSuccess();
}

// Same primitives, nodes, child references and root (height fields are not compared).
inline ::testing::AssertionResult sameStructure(const DensityField& a, const DensityField& b) {
    if (a.root != b.root) return ::testing::AssertionFailure() << "root " << a.root << " vs " << b.root;
    if (a.primitives.size() != b.primitives.size())
        return ::testing::AssertionFailure()
               << a.primitives.size() << " vs " << b.primitives.size() << " primitives";
    for (size_t i = 0; i < a.primitives.size(); ++i)
        if (auto r = samePrimitive(a.primitives[i], b.primitives[i]); !r) return r << " of primitive " << i;
    if (a.nodes.size() != b.nodes.size())
        return ::testing::AssertionFailure() << a.nodes.size() << " vs " << b.nodes.size() << " nodes";
    for (size_t n = 0; n < a.nodes.size(); ++n)
        if (a.nodes[n].op != b.nodes[n].op || a.nodes[n].first_child != b.nodes[n].first_child ||
            a.nodes[n].child_count != b.nodes[n].child_count)
            return ::testing::AssertionFailure() << "node " << n;
    if (a.children != b.children) return ::testing::AssertionFailure() << "child references";
    return ::testing::AssertionSuccess();
}

// evaluate() and evaluateWithGradient() agree bit for bit at `count` random points of `box`, and at
// least `min_nonzero` of the values are not 0 (so the comparison is not vacuous).
inline ::testing::AssertionResult sameValues(const DensityField& a, const DensityField& b, const Bounds& box,
                                             int min_nonzero = 1, int count = 2000, uint32_t seed = 1) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    int nonzero = 0;
    for (int k = 0; k < count; ++k) {
        const glm::vec3 p = box.lo + (box.hi - box.lo) * glm::vec3(u(rng), u(rng), u(rng));
        const float va = evaluate(a, p), vb = evaluate(b, p);
        if (!sameBits(va, vb))
            return ::testing::AssertionFailure()
                   << "value at (" << p.x << ", " << p.y << ", " << p.z << "): " << va << " vs " << vb;
        const glm::vec4 ga = evaluateWithGradient(a, p), gb = evaluateWithGradient(b, p);
        if (std::memcmp(&ga, &gb, sizeof(ga)) != 0)
            return ::testing::AssertionFailure()
                   << "gradient at (" << p.x << ", " << p.y << ", " << p.z << ")";
        nonzero += va != 0.0f;
    }
    if (nonzero < min_nonzero)
        return ::testing::AssertionFailure()
               << "only " << nonzero << " of " << count << " samples are non-zero";
    return ::testing::AssertionSuccess() << nonzero << " non-zero samples";
}

}  // namespace ug::test
