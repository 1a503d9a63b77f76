#include "instancer/instancing_settings.h"

namespace ug {

const char* priorityStrategyName(PriorityStrategy s) {
    switch (s) {
        case PriorityStrategy::Random: return "random";
        case PriorityStrategy::Elevation: return "elevation";
        case PriorityStrategy::DistanceToBoundary: return "distance_to_boundary";
    }
    return "unknown";
}

}  // namespace ug
