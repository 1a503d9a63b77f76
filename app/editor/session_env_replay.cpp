// Replay actions on the environmental objects (replay.h: env_add, env_move, env_remove, env_global,
// footprints, weather_stroke), through the same code as the Environment window and the view's tools: the
// drag and the weather brushes on rays straight down, one position a frame, one undo step each.
#include <cmath>

#include "editor/editor_session.h"

namespace ug::editor {

namespace {

// Points along a polyline every `spacing` metres (and its last point).
std::vector<glm::vec2> alongPolyline(const std::vector<glm::vec2>& points, float spacing) {
    std::vector<glm::vec2> out{points.front()};
    for (size_t i = 1; i < points.size(); ++i) {
        const glm::vec2 a = points[i - 1], b = points[i];
        const int n = std::max(1, int(std::ceil(glm::length(b - a) / spacing)));
        for (int k = 1; k <= n; ++k) out.push_back(a + (b - a) * (float(k) / float(n)));
    }
    return out;
}

}  // namespace

bool EditorSession::startEnvReplayAction(const ReplayAction& a) {
    windows.environment = true;  // the edits show there, as for the menu
    if (!live_environment) {
        *error = std::string(replayKindName(a.kind)) + ": the document has no environmental-object types";
        return false;
    }
    std::string op_error;
    const EnvironmentDesc& env = doc->project().environment;
    if (a.kind == ReplayKind::EnvRemove && a.node >= env.roots.size()) {
        *error = std::string(replayKindName(a.kind)) + ": no node " + std::to_string(a.node) + " (the tree has " +
                 std::to_string(env.roots.size()) + " at its top)";
        return false;
    }
    replay.finishing = true;
    switch (a.kind) {
        case ReplayKind::EnvAdd: {
            EnvironmentDesc edited = env;
            EnvNode node;
            node.type = uint32_t(std::find_if(env.types.begin(), env.types.end(),
                                              [&](const EnvTypeDesc& t) { return t.name == a.type; }) -
                                 env.types.begin());
            if (node.type >= env.types.size()) {
                *error = "env_add: no environmental-object type '" + a.type + "'";
                return false;
            }
            node.transform.translation = glm::vec3(a.at_xy, std::isnan(a.at_z) ? groundZ(a.at_xy) : a.at_z);
            if (a.on_surface) placementPoint(*doc, rayDownOnto(*doc, a.at_xy), &node.transform.translation);
            if (!std::isnan(a.yaw_deg)) node.transform.yaw_deg = a.yaw_deg;
            node.transform.scale = a.env_scale;
            const glm::vec3 at = node.transform.translation;
            replay.record["at"] = {at.x, at.y, at.z};
            edited.roots.push_back(std::move(node));
            replay.record["node"] = edited.roots.size() - 1;
            replay.record["ok"] = doc->setEnvironment(edited, "Add " + a.type, &op_error);
            environment_panel.selected = {uint32_t(edited.roots.size() - 1)};
            break;
        }
        case ReplayKind::EnvTree: {
            // The Environment window's tree buttons and drag and drop, on the same edits.
            EnvironmentDesc edited = env;
            bool ok = false;
            const char* name = nullptr;  // the window's undo names
            if (a.op == "group") {
                ok = groupEnvNode(&edited, a.node_path, &op_error);
                name = "Group";
            } else if (a.op == "ungroup") {
                ok = ungroupEnvNode(&edited, a.node_path, &op_error);
                name = "Ungroup";
            } else if (a.op == "into") {
                ok = moveEnvNodeInto(&edited, a.node_path, a.group_path, nullptr, &op_error);
                name = "Move into group";
            } else if (a.op == "reusable") {
                ok = makeEnvGroupReusable(&edited, a.node_path, a.name, &op_error);
                name = "Make group reusable";
            } else {
                ok = addEnvReference(&edited, a.name, EnvTransform{glm::vec3(a.at_xy, groundZ(a.at_xy)), 0.0f, 1.0f}, &op_error);
                name = "Instance group";
            }
            replay.record["ok"] = ok && doc->setEnvironment(edited, name, &op_error);
            break;
        }
        case ReplayKind::EnvRemove: {
            EnvironmentDesc edited = env;
            edited.roots.erase(edited.roots.begin() + std::ptrdiff_t(a.node));
            replay.record["ok"] = doc->setEnvironment(edited, "Delete object", &op_error);
            environment_panel.selected.clear();
            break;
        }
        case ReplayKind::EnvGlobal: {
            EnvironmentDesc edited = env;
            EnvChannel channel = EnvChannel::Snow;
            envChannelFromName(a.channel, &channel);  // checked when the script was read
            auto it = std::find_if(edited.global_fields.begin(), edited.global_fields.end(),
                                   [&](const EnvFieldDesc& f) { return f.everywhere && f.channel == channel; });
            if (it == edited.global_fields.end()) {
                EnvFieldDesc f;
                f.channel = channel;
                f.everywhere = true;
                it = edited.global_fields.insert(edited.global_fields.end(), f);
            }
            it->value = a.value;
            replay.record["ok"] = doc->setEnvironment(edited, "Set " + a.channel, &op_error);
            break;
        }
        case ReplayKind::EnvMove:
        case ReplayKind::EnvHandle: {
            // The node's origin (a move) or the handle's point, dragged to "to" in `steps` frames.
            EnvHandleFrame frame;
            const EnvHandle handle = a.handle == "turn" ? EnvHandle::Turn : EnvHandle::Scale;
            if (!envNodeAt(env, a.node_path) || (a.kind == ReplayKind::EnvHandle && !envHandleFrame(*doc, a.node_path, &frame))) {
                *error = std::string(replayKindName(a.kind)) + ": no node " + envPathText(a.node_path);
                return false;
            }
            const glm::vec3 from = a.kind == ReplayKind::EnvMove ? envWorldTransform(env, a.node_path).translation
                                                                 : envHandlePoint(frame, handle);
            environment_panel.selected = a.node_path;
            replay.record["from"] = {from.x, from.y, from.z};
            replay.path.clear();
            for (int k = 1; k <= a.steps; ++k)
                replay.path.push_back(glm::mix(glm::vec2(from), a.at_xy, float(k) / float(a.steps)));
            replay.step = 0;
            const bool begun = a.kind == ReplayKind::EnvMove
                                   ? env_drag.begin(doc, a.node_path, rayDownOnto(*doc, glm::vec2(from)))
                                   : env_handle_drag.begin(doc, a.node_path, handle, rayDownOnto(*doc, glm::vec2(from)));
            if (!begun) op_error = std::string(replayKindName(a.kind)) + ": could not grab " + envPathText(a.node_path);
            replay.finishing = !begun;
            break;
        }
        case ReplayKind::Footprints:
        case ReplayKind::WeatherStroke: {
            WeatherSettings weather;
            if (a.kind == ReplayKind::WeatherStroke) {
                weatherBrushFromName(a.brush, &weather.brush);  // checked when the script was read
                weather.radius_m = a.radius_m;
                weather.strength = a.strength;
            }
            const glm::vec2 start = a.points.front();
            // Half a stamp's spacing a frame, so the stroke's path is followed closely.
            const float spacing = weather.brush == WeatherBrush::Footprints ? kFootprintStrideM : 0.5f * weather.radius_m;
            replay.path = alongPolyline(a.points, 0.5f * spacing);
            replay.step = 1;
            replay.finishing = false;
            if (!weather_stroke.begin(doc, weather, glm::vec3(start, groundZ(start)), &op_error)) replay.finishing = true;
            break;
        }
        default:
            break;
    }
    if (!op_error.empty()) {
        replay.record["error"] = op_error;
        messages.push_back(op_error);
    }
    return true;
}

void EditorSession::stepEnvReplay() {
    std::string op_error;
    if (replay.step < replay.path.size()) {
        const uint64_t generation = doc->environmentGeneration();
        const glm::vec2 xy = replay.path[replay.step];
        const bool snap = options.replay[replay.index].snap;
        const bool ok = env_drag.active()          ? env_drag.drag(rayDownOnto(*doc, xy), &op_error)
                        : env_handle_drag.active() ? env_handle_drag.drag(rayDownOnto(*doc, xy), snap, &op_error)
                                                   : weather_stroke.drag(glm::vec3(xy, groundZ(xy)), &op_error);
        if (!ok) messages.push_back(op_error);
        noteEnvStamp(generation, int(replay.index));
    }
    if (++replay.step < replay.path.size()) return;
    if (env_drag.active()) {
        const glm::vec3 to = envWorldTransform(doc->project().environment, env_drag.path()).translation;
        replay.record["moves"] = env_drag.moves();
        replay.record["to"] = {to.x, to.y, to.z};
        env_drag.end();
    } else if (env_handle_drag.active()) {
        const EnvTransform world = envWorldTransform(doc->project().environment, environment_panel.selected);
        replay.record["moves"] = env_handle_drag.moves();
        replay.record["yaw_deg"] = world.yaw_deg;
        replay.record["scale"] = world.scale;
        env_handle_drag.end();
    } else {
        replay.record["stamps"] = weather_stroke.stamps();
        replay.record["erased"] = weather_stroke.erased();
        weather_stroke.end();
    }
    replay.finishing = true;
}

}  // namespace ug::editor
