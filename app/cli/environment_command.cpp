// undergrowth environment SCENE --at x,y,z [--at x,y,z ...]: the environment e(p) (the eight channels and
// the shelter) and the terrain's height under each point (null without a terrain) at world points, as JSON
// on stdout, for pipelines, scene generators (objects set on the ground) and tests. Loads only what the
// environment needs (the project, its terrain and the environmental objects), not the Ghost Tile.
#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/cli_args.h"
#include "cli/commands.h"
#include "env/env_scene.h"
#include "scene/field_json.h"
#include "scene/project.h"
#include "scene/scene_compile.h"

namespace ug::cli {

namespace {

int usage(const std::string& why) {
    std::fprintf(stderr, "undergrowth environment: %s\nusage: undergrowth environment SCENE --at x,y,z [--at x,y,z ...]\n",
                 why.c_str());
    return 2;
}

nlohmann::json sampleJson(glm::vec3 p, const EnvSample& e, const HeightField* terrain) {
    return {{"at", {jsonFloat(p.x), jsonFloat(p.y), jsonFloat(p.z)}},
            {"ground", terrain ? jsonFloat(terrain->sample(p.x, p.y)) : nlohmann::json(nullptr)},
            {"snow", jsonFloat(e.snow)},
            {"icicles", jsonFloat(e.icicles)},
            {"leaves", jsonFloat(e.leaves)},
            {"grass", jsonFloat(e.grass)},
            {"trash", jsonFloat(e.trash)},
            {"occlusion", jsonFloat(e.occlusion)},
            {"humidity", jsonFloat(e.humidity)},
            {"temperature", jsonFloat(e.temperature)},
            {"shelter", jsonFloat(e.shelter)}};
}

}  // namespace

int runEnvironmentCommand(int argc, char** argv) {
    std::string scene;
    std::vector<glm::vec3> points;
    for (int i = 2; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--at") {
            if (i + 1 >= argc) return usage("--at needs x,y,z");
            std::vector<double> v;
            std::string error;
            if (!parseNumberList("--at", argv[++i], &v, &error)) return usage(error);
            if (v.size() != 3) return usage("--at expects three numbers x,y,z, got " + std::to_string(v.size()));
            points.push_back(glm::vec3(float(v[0]), float(v[1]), float(v[2])));
        } else if (a.rfind("--", 0) == 0) {
            return usage("unknown option " + a);
        } else if (scene.empty()) {
            scene = a;
        } else {
            return usage("one scene only (got '" + scene + "' and '" + a + "')");
        }
    }
    if (scene.empty()) return usage("no scene given");
    if (points.empty()) return usage("no --at point given");
    std::string error;
    Project project;
    std::shared_ptr<const HeightField> terrain;
    EnvScene env;
    if (!loadProject(scene, &project, &error) || !loadTerrain(project, &terrain, &error) ||
        !compileEnvScene(project.environment, project.base_dir, scene, terrain, &env, &error)) {
        std::fprintf(stderr, "undergrowth environment: %s\n", error.c_str());
        return 1;
    }
    nlohmann::json out = {{"scene", scene}, {"objects", env.objects().size()}, {"fields", env.fields().size()}};
    nlohmann::json samples = nlohmann::json::array();
    for (glm::vec3 p : points) samples.push_back(sampleJson(p, env.sample(p), terrain.get()));
    out["points"] = samples;
    std::printf("%s\n", out.dump(2).c_str());
    return 0;
}

}  // namespace ug::cli
