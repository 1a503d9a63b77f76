// Statistics of the editor's session (viewer.h ViewerResult, the --stats file): what a replay action or a
// mouse stroke left, measured the way check_edit.py and check_panels.py judge them. GL-free: every function
// reads a Document or an InstanceStore.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "editor/tools.h"
#include "instancer/instance_store.h"
#include "scene/document.h"

namespace ug::editor {

// A finished sculpt stroke's pile as the user would judge it (tools.h measureSculptedPile), around the
// ground point of its first stamp, and how many primitives the stroke left (one per cone): "found", "type",
// "ground_point", "centroid", "height", "radius", "volume", "angle_of_repose_deg", "stamps", "primitives",
// "ids".
nlohmann::json pileRecord(const Document& doc, const BrushStroke& stroke);
// The pile as its instances show it: the sculpt type's instances whose origin lies within 1.25 pile radii
// (horizontally) of the ground point: "count", "centroid", "top" (the highest origin above the ground).
nlohmann::json pileInstancesJson(const Document& doc, const InstanceStore& store, const nlohmann::json& pile);

// {name: count} in type order.
nlohmann::json perTypeJson(const std::vector<std::string>& names, const std::vector<uint64_t>& counts);
std::vector<uint64_t> perTypeCounts(const InstanceStore& store, const CandidateSet& candidates);
// How far an instance's collision spheres reach from its origin, at most, over all types.
float largestReach(const Document& doc);

nlohmann::json vec3Json(glm::vec3 v);
// Where a world point lands on screen, in pixels from the top left (NaN behind the eye).
glm::vec2 projectToPixel(const glm::mat4& view_proj, float width, float height, glm::vec3 p);

}  // namespace ug::editor
