// The project (scene) document: what the user edits and saves. It stores settings, models by path,
// seeds and (from the instantiation issue on) density primitives, never instances, so a project stays
// a few kilobytes however many objects it makes (DESIGN.md, "what users of the peers complain about").
//
// File: JSON, {"format": "undergrowth-project", "format_version": 1, ...}; see assets/scenes/*.json.
// Relative paths inside a project are relative to the project file's folder.
#pragma once

#include <string>
#include <vector>

#include "ghosttile/ghost_tile.h"
#include "mesh/detail_model.h"

namespace ug {

constexpr int kProjectFormatVersion = 1;

struct DetailTypeDesc {
    DetailModelSource model;    // model.name is the type's name
    DetailTypeSettings ghost;   // ghost.name == model.name
};

struct Project {
    std::string name;
    GhostTileSettings ghost_tile;
    std::vector<DetailTypeDesc> detail_types;
    std::string base_dir;  // folder of the file it was loaded from (not saved)
};

// Errors: "<path>: <JSON pointer>: <reason>", e.g.
// "meadow.json: /detail_types/1/candidates/scale: expected [min, max] with 0 < min <= max".
bool loadProject(const std::string& path, Project* out, std::string* error);
bool parseProject(const std::string& text, const std::string& source_name, Project* out, std::string* error);
std::string projectToJson(const Project& project);
bool saveProject(const std::string& path, const Project& project, std::string* error);  // atomic

// Loads every detail type's model (fitting sphere sets) and assembles the Ghost Tile input.
// `models` receives the loaded models; input.models points into it (keep it alive).
bool loadProjectModels(const Project& project, std::vector<DetailModel>* models, std::string* error);
GhostTileInput ghostTileInput(const Project& project, const std::vector<DetailModel>& models);

// Resolves a project-relative path.
std::string resolveProjectPath(const Project& project, const std::string& path);

}  // namespace ug
