#include "env/env_desc.h"

namespace ug {

namespace {
constexpr const char* kChannelNames[kEnvChannelCount] = {"snow",  "icicles",   "leaves",   "grass",
                                                         "trash", "occlusion", "humidity", "temperature"};
}

const char* envChannelName(EnvChannel c) { return kChannelNames[size_t(c)]; }

bool envChannelFromName(const std::string& name, EnvChannel* out) {
    for (size_t i = 0; i < kEnvChannelCount; ++i)
        if (name == kChannelNames[i]) {
            *out = EnvChannel(i);
            return true;
        }
    return false;
}

const char* snowModeName(SnowMode m) {
    switch (m) {
    case SnowMode::None: return "none";
    case SnowMode::Geometry: return "geometry";
    case SnowMode::Box: return "box";
    case SnowMode::Cylinder: return "cylinder";
    case SnowMode::Sphere: return "sphere";
    }
    return "?";
}

bool EffectOverrides::empty() const {
    return !snow_mode && !snow_max_face_angle_deg && !snow_d0_m && !snow_target_edge_m && !icicles_enabled &&
           !icicle_spacing_m && !icicle_max_length_m;
}

}  // namespace ug
