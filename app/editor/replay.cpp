#include "editor/replay.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <string>
#include <string_view>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "editor/env_tools.h"
#include "editor/panels.h"
#include "env/env_desc.h"
#include "scene/project.h"

namespace ug::editor {

using nlohmann::json;

const char* replayKindName(ReplayKind kind) {
    switch (kind) {
        case ReplayKind::PaintStroke:
            return "paint_stroke";
        case ReplayKind::SculptStroke:
            return "sculpt_stroke";
        case ReplayKind::EraseStroke:
            return "erase_stroke";
        case ReplayKind::Undo:
            return "undo";
        case ReplayKind::Redo:
            return "redo";
        case ReplayKind::Save:
            return "save";
        case ReplayKind::SaveAs:
            return "save_as";
        case ReplayKind::Screenshot:
            return "screenshot";
        case ReplayKind::View:
            return "view";
        case ReplayKind::Move:
            return "move";
        case ReplayKind::WaitIdle:
            return "wait_idle";
        case ReplayKind::GhostTile:
            return "ghost_tile";
        case ReplayKind::SetSeed:
            return "set_seed";
        case ReplayKind::SetInstancing:
            return "set_instancing";
        case ReplayKind::Export:
            return "export";
        case ReplayKind::Open:
            return "open";
        case ReplayKind::New:
            return "new";
        case ReplayKind::SetVisible:
            return "set_visible";
        case ReplayKind::SetAttractor:
            return "set_attractor";
        case ReplayKind::EnvAdd:
            return "env_add";
        case ReplayKind::EnvMove:
            return "env_move";
        case ReplayKind::EnvRemove:
            return "env_remove";
        case ReplayKind::EnvGlobal:
            return "env_global";
        case ReplayKind::Footprints:
            return "footprints";
        case ReplayKind::WeatherStroke:
            return "weather_stroke";
        case ReplayKind::ShowWindow:
            return "show_window";
        case ReplayKind::EnvView:
            return "env_view";
        case ReplayKind::EnvTree:
            return "env_tree";
        case ReplayKind::EnvHandle:
            return "env_handle";
        case ReplayKind::ParticleEntry:
            return "particle_entry";
    }
    return "?";
}

bool editsEnvironment(ReplayKind kind) {
    switch (kind) {
        case ReplayKind::EnvAdd:
        case ReplayKind::EnvMove:
        case ReplayKind::EnvHandle:
        case ReplayKind::EnvRemove:
        case ReplayKind::EnvGlobal:
        case ReplayKind::EnvTree:
        case ReplayKind::Footprints:
        case ReplayKind::WeatherStroke: return true;
        default: return false;
    }
}

bool loadReplayScript(const std::string& path, std::vector<ReplayAction>* out, std::string* error) {
    std::string text;
    if (!readTextFile(path, &text, error)) return false;
    return parseReplayScript(text, path, out, error);
}

namespace {

// The keys each action reads besides "action" and "frame". A key outside its action's list is refused: a
// script that said "yaw" for "yaw_deg" used to run from the default camera and silently screenshot the
// wrong view, and one that gave a `view` a "to" (a move's key) was as silently ignored.
std::vector<std::string_view> replayKeysOf(ReplayKind kind) {
    switch (kind) {
        case ReplayKind::PaintStroke:
        case ReplayKind::SculptStroke:
        case ReplayKind::EraseStroke:
            return {"points", "type", "types", "radius", "strength", "falloff", "subtract", "steps", "surface",
                    "from_camera"};
        case ReplayKind::Undo:
        case ReplayKind::Redo:
        case ReplayKind::Save:
        case ReplayKind::WaitIdle:
        case ReplayKind::New: return {};
        case ReplayKind::SaveAs:
        case ReplayKind::Open: return {"path"};
        case ReplayKind::Screenshot: return {"path", "ui", "overlays"};
        case ReplayKind::View: return {"target", "distance", "yaw_deg", "pitch_deg"};
        case ReplayKind::Move: return {"from", "to", "steps"};
        case ReplayKind::GhostTile:
            return {"type", "types", "count", "delta", "tile_size", "model", "model_scale", "scale", "seed"};
        case ReplayKind::SetSeed: return {"seed"};
        case ReplayKind::SetInstancing: return {"type", "strategy", "layer", "orientation", "size"};
        case ReplayKind::Export: return {"path", "plain_nodes", "chunk"};
        case ReplayKind::SetVisible: return {"type", "node", "visible"};
        case ReplayKind::SetAttractor: return {"system", "attractor", "a_m", "influence", "charge", "cancel"};
        case ReplayKind::ParticleEntry: return {"system", "name", "offset_m"};
        case ReplayKind::EnvAdd: return {"type", "at", "yaw_deg", "scale", "on_surface"};
        case ReplayKind::EnvMove: return {"node", "to", "steps"};
        case ReplayKind::EnvHandle: return {"node", "to", "steps", "handle", "snap"};
        case ReplayKind::EnvRemove: return {"node"};
        case ReplayKind::EnvGlobal: return {"channel", "value"};
        case ReplayKind::Footprints: return {"points"};
        case ReplayKind::WeatherStroke: return {"points", "brush", "radius", "strength"};
        case ReplayKind::ShowWindow: return {"window", "open"};
        case ReplayKind::EnvView: return {"channel", "height", "surfaces"};
        case ReplayKind::EnvTree: return {"op", "name", "node", "group", "at"};
    }
    return {};
}

bool readByAction(ReplayKind kind, std::string_view key) {
    const std::vector<std::string_view> keys = replayKeysOf(kind);
    return key == "action" || key == "frame" || std::find(keys.begin(), keys.end(), key) != keys.end();
}

// The first key of action `a` (of kind `kind`) that it does not read, why, and a hint: the actions that
// do read it, or the action's own key it looks like ("yaw" -> "yaw_deg"); empty when every key is read.
std::string unreadReplayKey(ReplayKind kind, const json& a) {
    for (const auto& [key, value] : a.items()) {
        (void)value;
        if (readByAction(kind, key)) continue;
        std::string readers;
        for (int k = 0; k < kReplayKindCount; ++k)
            if (readByAction(ReplayKind(k), key))
                readers += std::string(readers.empty() ? "" : ", ") + replayKindName(ReplayKind(k));
        const std::string action = replayKindName(kind);
        if (!readers.empty()) return "\"" + action + "\" does not read \"" + key + "\" (read by " + readers + ")";
        std::string why = "unknown key \"" + key + "\"";
        for (std::string_view known : replayKeysOf(kind)) {
            const std::string k(known);
            if (!key.empty() && (k.rfind(key, 0) == 0 || key.rfind(k, 0) == 0)) {
                why += " (did you mean \"" + k + "\"?)";
                break;
            }
        }
        return why;
    }
    return {};
}

}  // namespace

bool parseReplayScript(const std::string& text, const std::string& path, std::vector<ReplayAction>* out,
                       std::string* error) {
    const json j = json::parse(text, nullptr, false);
    if (!j.is_array()) {
        *error = path + ": expected a JSON list of actions";
        return false;
    }
    std::vector<ReplayAction> actions;
    for (size_t i = 0; i < j.size(); ++i) {
        const json& a = j[i];
        const std::string where = path + ": action " + std::to_string(i) + ": ";
        auto fail = [&](const std::string& why) {
            *error = where + why;
            return false;
        };
        if (!a.is_object() || !a.contains("action") || !a["action"].is_string())
            return fail("needs \"action\"");
        ReplayAction r;
        const std::string name = a["action"].get<std::string>();
        bool known = false;
        for (int k = 0; k < kReplayKindCount; ++k)
            if (name == replayKindName(ReplayKind(k))) {
                r.kind = ReplayKind(k);
                known = true;
            }
        if (!known) return fail("unknown action '" + name + "'");
        if (const std::string why = unreadReplayKey(r.kind, a); !why.empty()) return fail(why);
        try {
            r.frame = a.value("frame", -1);
            r.radius_m = a.value("radius", r.radius_m);
            r.strength = a.value("strength", r.strength);
            r.falloff_m = a.value("falloff", r.falloff_m);
            r.subtract = a.value("subtract", false);
            r.steps = a.value("steps", r.steps);
            r.path = a.value("path", std::string());
            r.surface = a.value("surface", std::string());
            r.from_camera = a.value("from_camera", false);
            r.overlays = a.value("overlays", true);
            r.ui = a.value("ui", false);
            if (a.contains("type")) r.types[a["type"].get<std::string>()] = 1.0f;
            if (a.contains("types"))
                for (const auto& [k, v] : a["types"].items()) r.types[k] = v.get<float>();
            if (a.contains("points"))
                for (const json& p : a["points"])
                    r.points.push_back(glm::vec2(p.at(0).get<float>(), p.at(1).get<float>()));
            if (a.contains("from") && a.contains("to")) {
                for (const char* key : {"from", "to"})
                    r.points.push_back(glm::vec2(a[key].at(0).get<float>(), a[key].at(1).get<float>()));
            }
            if (a.contains("target")) {
                const json& t = a["target"];
                r.has_target = true;
                r.target = glm::vec3(t.at(0).get<float>(), t.at(1).get<float>(),
                                     t.size() > 2 ? t.at(2).get<float>() : 0.0f);
            }
            r.distance_m = a.value("distance", -1.0f);
            if (a.contains("yaw_deg")) r.yaw_deg = a["yaw_deg"].get<float>();
            if (a.contains("pitch_deg")) r.pitch_deg = a["pitch_deg"].get<float>();
            if (r.kind == ReplayKind::GhostTile) {
                ReplayAction::GhostTileEdit& g = r.ghost;
                g.count = a.value("count", int64_t(-1));
                g.delta_m = a.value("delta", NAN);
                g.tile_size_m = a.value("tile_size", NAN);
                g.model_scale = a.value("model_scale", NAN);
                g.model_path = a.value("model", std::string());
                if (a.contains("scale")) {
                    g.scale_min = a["scale"].at(0).get<float>();
                    g.scale_max = a["scale"].at(1).get<float>();
                }
                if (a.contains("seed")) {
                    g.has_seed = true;
                    g.seed = a["seed"].get<uint64_t>();
                }
            }
            if (r.kind == ReplayKind::SetSeed) r.seed = a.at("seed").get<uint64_t>();
            if (r.kind == ReplayKind::ParticleEntry) {
                r.system = a.value("system", size_t(0));
                if (a.contains("name")) r.entry_name = a["name"].get<std::string>();
                if (a.contains("offset_m"))
                    r.entry_offset = glm::vec3(a["offset_m"].at(0).get<float>(), a["offset_m"].at(1).get<float>(),
                                               a["offset_m"].at(2).get<float>());
            }
            if (r.kind == ReplayKind::SetAttractor) {
                r.system = a.value("system", size_t(0));
                r.attractor = a.value("attractor", size_t(0));
                if (a.contains("a_m")) {
                    r.has_a = true;
                    r.a_m = glm::vec3(a["a_m"].at(0).get<float>(), a["a_m"].at(1).get<float>(), a["a_m"].at(2).get<float>());
                }
                r.influence_m = a.value("influence", NAN);
                r.charge = a.value("charge", NAN);
                r.cancel = a.value("cancel", false);
            }
            if (r.kind == ReplayKind::EnvAdd || r.kind == ReplayKind::EnvMove || r.kind == ReplayKind::EnvHandle) {
                const json& at = a.at(r.kind == ReplayKind::EnvAdd ? "at" : "to");
                r.at_xy = glm::vec2(at.at(0).get<float>(), at.at(1).get<float>());
                if (r.kind == ReplayKind::EnvAdd && at.size() > 2) r.at_z = at.at(2).get<float>();
            }
            if (r.kind == ReplayKind::EnvAdd) r.env_scale = a.value("scale", 1.0f);
            if (r.kind == ReplayKind::EnvAdd) r.on_surface = a.value("on_surface", false);
            if (r.kind == ReplayKind::EnvAdd) r.type = a.at("type").get<std::string>();
            if (r.kind == ReplayKind::EnvRemove) r.node = a.at("node").get<size_t>();
            if (r.kind == ReplayKind::EnvMove || r.kind == ReplayKind::EnvHandle) {
                const json& n = a.at("node");  // a top-level index or a path
                r.node_path = n.is_array() ? n.get<std::vector<uint32_t>>() : std::vector<uint32_t>{n.get<uint32_t>()};
            }
            if (r.kind == ReplayKind::EnvHandle) {
                r.handle = a.at("handle").get<std::string>();
                r.snap = a.value("snap", false);
            }
            if (r.kind == ReplayKind::EnvGlobal) {
                r.channel = a.at("channel").get<std::string>();
                r.value = a.at("value").get<float>();
            }
            if (r.kind == ReplayKind::SetVisible) {
                // A detail type's layer, or an environmental node (the Outliner's eyes).
                if (a.contains("node")) {
                    const json& n = a["node"];
                    r.node_path = n.is_array() ? n.get<std::vector<uint32_t>>() : std::vector<uint32_t>{n.get<uint32_t>()};
                } else {
                    r.type = a.at("type").get<std::string>();
                }
                r.visible = a.at("visible").get<bool>();
                r.types.clear();
            }
            if (r.kind == ReplayKind::SetInstancing) {
                r.type = a.at("type").get<std::string>();
                r.types.clear();
                r.instancing_json = a.dump();
            }
            r.plain_nodes = a.value("plain_nodes", false);
            r.chunk_m = a.value("chunk", -1.0f);
        } catch (const json::exception& e) {
            return fail(std::string("bad value: ") + e.what());
        }
        const bool stroke = r.kind == ReplayKind::PaintStroke || r.kind == ReplayKind::SculptStroke ||
                            r.kind == ReplayKind::EraseStroke;
        if (stroke) {
            if (r.points.empty()) return fail("a stroke needs \"points\" [[x, y], ...]");
            if (r.types.empty()) return fail("a stroke needs \"type\" or \"types\"");
            if (!(r.radius_m > 0.0f) || !(r.strength > 0.0f) || !(r.falloff_m > 0.0f))
                return fail("radius, strength and falloff must be > 0");
            if (r.steps < 1 || r.steps > 100000) return fail("steps must be in [1, 100000]");
        }
        if (r.kind == ReplayKind::WeatherStroke) r.brush = a.value("brush", r.brush);
        if (r.kind == ReplayKind::EnvTree) {
            try {
                r.op = a.at("op").get<std::string>();
                r.name = a.value("name", std::string());
                if (a.contains("node")) r.node_path = a["node"].get<std::vector<uint32_t>>();
                if (a.contains("group")) r.group_path = a["group"].get<std::vector<uint32_t>>();
                if (a.contains("at")) r.at_xy = glm::vec2(a["at"].at(0).get<float>(), a["at"].at(1).get<float>());
            } catch (const json::exception& e) {
                return fail(std::string("env_tree: ") + e.what());
            }
            const bool op_known = r.op == "group" || r.op == "ungroup" || r.op == "into" || r.op == "reusable" ||
                               r.op == "instance";
            if (!op_known) return fail("env_tree: unknown op '" + r.op + "'");
            if (r.op != "instance" && r.node_path.empty()) return fail("env_tree: " + r.op + " needs \"node\"");
            if (r.op == "into" && r.group_path.empty()) return fail("env_tree: into needs \"group\"");
        }
        if (r.kind == ReplayKind::EnvView) {
            r.channel = a.value("channel", std::string("snow"));
            r.value = a.value("height", 0.05f);
            r.on_surface = a.value("surfaces", true);
            int c = 0;
            if (r.channel != "off" && !channelMapFromName(r.channel, &c)) return fail("unknown channel '" + r.channel + "'");
        }
        if (r.kind == ReplayKind::ShowWindow) {
            r.window = a.value("window", std::string());
            r.visible = a.value("open", true);
            WindowToggles probe;
            if (!windowToggle(&probe, r.window)) return fail("unknown window '" + r.window + "'");
        }
        if ((r.kind == ReplayKind::Footprints || r.kind == ReplayKind::WeatherStroke) && r.points.empty())
            return fail(std::string(replayKindName(r.kind)) + " needs \"points\" [[x, y], ...]");
        if (r.kind == ReplayKind::WeatherStroke) {
            WeatherBrush brush;
            if (!weatherBrushFromName(r.brush, &brush)) return fail("unknown brush '" + r.brush + "'");
            if (!(r.radius_m > 0.0f) || !(r.strength > 0.0f)) return fail("radius and strength must be > 0");
        }
        if (r.kind == ReplayKind::EnvGlobal) {
            EnvChannel c;
            if (!envChannelFromName(r.channel, &c)) return fail("unknown channel '" + r.channel + "'");
        }
        if ((r.kind == ReplayKind::EnvMove || r.kind == ReplayKind::EnvHandle) && (r.steps < 1 || r.steps > 100000))
            return fail("steps must be in [1, 100000]");
        if ((r.kind == ReplayKind::EnvMove || r.kind == ReplayKind::EnvHandle) && r.node_path.empty())
            return fail("\"node\" must name a node (an index or a path)");
        if (r.kind == ReplayKind::EnvHandle && r.handle != "turn" && r.handle != "scale")
            return fail("unknown handle '" + r.handle + "' (turn or scale)");
        if (r.kind == ReplayKind::Move) {
            if (r.points.size() != 2) return fail("a move needs \"from\" [x, y] and \"to\" [x, y]");
            if (r.steps < 1 || r.steps > 100000) return fail("steps must be in [1, 100000]");
        }
        if ((r.kind == ReplayKind::SaveAs || r.kind == ReplayKind::Screenshot ||
             r.kind == ReplayKind::Export || r.kind == ReplayKind::Open) &&
            r.path.empty())
            return fail("needs \"path\"");
        if (r.kind == ReplayKind::SetInstancing) {
            InstancingDesc check;
            std::string why;
            if (!applyInstancingChanges(r.instancing_json, &check, &why)) return fail(why);
        }
        actions.push_back(std::move(r));
    }
    *out = std::move(actions);
    return true;
}

bool applyReplayGhostTile(const ReplayAction& a, GhostTileSpec* spec, std::string* error) {
    const ReplayAction::GhostTileEdit& g = a.ghost;
    if (!std::isnan(g.delta_m)) spec->settings.delta_m = g.delta_m;
    if (!std::isnan(g.tile_size_m)) spec->settings.tile_size_m = g.tile_size_m;
    if (g.has_seed) spec->settings.seed = g.seed;
    const bool per_type = g.count >= 0 || !std::isnan(g.scale_min) || !std::isnan(g.model_scale) ||
                          !g.model_path.empty();
    if (a.types.empty()) {
        if (!per_type) return true;
        *error = "replay: ghost_tile: count, scale, model and model_scale need \"type\"";
        return false;
    }
    for (const auto& [name, weight] : a.types) {
        (void)weight;
        size_t t = 0;
        while (t < spec->types.size() && spec->types[t].name != name) ++t;
        if (t == spec->types.size()) {
            *error = "replay: ghost_tile: no detail type '" + name + "'";
            return false;
        }
        // Clamped only to the field's range: an absurd count must reach the validation and its message.
        if (g.count >= 0) spec->types[t].candidate_count = uint32_t(std::min<int64_t>(g.count, UINT32_MAX));
        if (!std::isnan(g.scale_min)) {
            spec->types[t].scale_min = g.scale_min;
            spec->types[t].scale_max = g.scale_max;
        }
        if (!std::isnan(g.model_scale)) spec->models[t].scale = g.model_scale;
        if (!g.model_path.empty()) spec->models[t].mesh_path = g.model_path;
    }
    return true;
}

bool applyInstancingChanges(const std::string& action_json, InstancingDesc* desc, std::string* error) {
    const json a = json::parse(action_json, nullptr, false);
    InstancingDesc d = *desc;
    try {
        if (a.contains("strategy")) {
            const std::string name = a["strategy"].get<std::string>();
            bool known = false;
            for (const PriorityStrategy s : {PriorityStrategy::Random, PriorityStrategy::Elevation,
                                             PriorityStrategy::DistanceToBoundary})
                if (name == priorityStrategyName(s)) {
                    d.strategy = s;
                    known = true;
                }
            if (!known) {
                *error = "strategy: unknown '" + name + "' (random, elevation or distance_to_boundary)";
                return false;
            }
        }
        if (a.contains("layer")) d.layer_m = a["layer"].get<float>();
        if (a.contains("orientation")) {
            const json& o = a["orientation"];
            d.orientation.enabled = !o.is_boolean() || o.get<bool>();
            if (o.is_object()) {
                if (o.contains("direction")) {
                    const json& dir = o["direction"];
                    if (dir.is_string() && dir.get<std::string>() == "gradient") {
                        d.orientation.kind = DirectionFieldKind::Gradient;
                    } else {
                        d.orientation.kind = DirectionFieldKind::Constant;
                        d.orientation.direction = glm::normalize(glm::vec3(
                            dir.at(0).get<float>(), dir.at(1).get<float>(), dir.at(2).get<float>()));
                    }
                }
                if (o.contains("max_angle_deg"))
                    d.orientation.max_angle_deg = o["max_angle_deg"].get<float>();
            }
        }
        if (a.contains("size")) {
            const json& z = a["size"];
            d.size.enabled = !z.is_boolean() || z.get<bool>();
            if (z.is_object()) {
                if (z.contains("target")) {
                    d.size.kind = SizeFieldKind::Constant;
                    d.size.target = z["target"].get<float>();
                }
                if (z.contains("tolerance")) d.size.tolerance = z["tolerance"].get<float>();
            }
        }
    } catch (const json::exception& e) {
        *error = std::string("bad instancing value: ") + e.what();
        return false;
    }
    *desc = d;
    return true;
}

std::vector<glm::vec2> strokePath(const ReplayAction& a) {
    std::vector<glm::vec2> out;
    if (a.points.empty()) return out;
    float length = 0.0f;
    for (size_t i = 1; i < a.points.size(); ++i) length += glm::length(a.points[i] - a.points[i - 1]);
    auto at = [&](float s) {
        for (size_t i = 1; i < a.points.size(); ++i) {
            const float l = glm::length(a.points[i] - a.points[i - 1]);
            if (s <= l && l > 0.0f) return glm::mix(a.points[i - 1], a.points[i], s / l);
            s -= l;
        }
        return a.points.back();
    };
    if (a.kind == ReplayKind::Move) {
        for (int k = 1; k <= a.steps; ++k)
            out.push_back(glm::mix(a.points.front(), a.points.back(), float(k) / float(a.steps)));
        return out;
    }
    if (a.kind == ReplayKind::SculptStroke) {
        for (int k = 0; k < a.steps; ++k)
            out.push_back(at(a.steps == 1 ? 0.0f : length * float(k) / float(a.steps - 1)));
        return out;
    }
    // A little more than the stamp spacing, so rounding never skips a stamp.
    const float step = 1.001f * a.radius_m / 3.0f;
    for (float s = 0.0f; s < length; s += step) out.push_back(at(s));
    out.push_back(a.points.back());
    return out;
}

}  // namespace ug::editor
