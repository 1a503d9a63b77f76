// Shared by the particle tests: a particle file whose "walk" is given, parsed, must be refused with an
// error naming `where` (a JSON Pointer, or a field the validation names).
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "particles/particle_json.h"

namespace ug::test {

inline void expectWalkRefused(const std::string& walk, const std::string& where) {
    const std::string text = R"({"format": "undergrowth-particles", "format_version": 1,
        "generators": [{"kind": "rectangle", "count": 4}], "walk": )" + walk + "}";
    ParticleSystemFile s;
    std::string error;
    EXPECT_FALSE(parseParticleSystem(nlohmann::json::parse(text), "bad.json", &s, &error)) << walk;
    EXPECT_NE(error.find(where), std::string::npos) << error;
}

}  // namespace ug::test
