// `undergrowth grow PARTICLES.json -o OUT.glb`: particle sculpting (docs/particles.md) from a particle
// system file to glTF. Grows the strands (a pure function of the file: the same bytes for any --threads),
// meshes them as closed tubes and writes one mesh "strands/<name>" with the system's material and the
// polylines in its extras (particles/particle_output.h).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>

#include <nlohmann/json.hpp>

#include "cli/cli_args.h"
#include "cli/commands.h"
#include "core/atomic_file.h"
#include "io/gltf_scene_export.h"
#include "particles/particle_json.h"
#include "particles/particle_output.h"

namespace ug::cli {

namespace {

namespace fs = std::filesystem;

int fail(const std::string& message, int code = 1) {
    std::fprintf(stderr, "undergrowth grow: %s\n", message.c_str());
    return code;
}

}  // namespace

int runGrowCommand(int argc, char** argv) {
    const char* usage = "usage: undergrowth grow PARTICLES.json -o OUT.glb|OUT.gltf [--stats FILE] [--threads N]";
    Args args;
    std::string error;
    if (!parseArgs(argc, argv, 2, {"-o", "--out", "--stats", "--threads"}, {}, &args, &error) ||
        args.positional.size() != 1)
        return fail(error.empty() ? usage : error + "\n" + usage, 2);
    const std::string out = args.has("-o") ? args.get("-o") : args.get("--out");
    if (out.empty()) return fail(std::string("missing -o OUT.glb\n") + usage, 2);
    const std::string ext = fs::path(out).extension().string();
    if (ext != ".glb" && ext != ".gltf") return fail(out + ": the output must end in .glb or .gltf", 2);
    long threads = 0;
    if (args.has("--threads") && !parseInt("--threads", args.get("--threads"), 0, 256, &threads, &error))
        return fail(error, 2);

    const std::string path = args.positional[0];
    ParticleSystemFile system;
    if (!loadParticleSystem(path, &system, &error)) return fail(error);
    const auto t0 = std::chrono::steady_clock::now();
    Strands strands;
    SceneExport scene;
    if (!appendParticleSystemMeshes(system, int(threads), &strands, &scene.meshes, &error))
        return fail(path + ": " + error);
    const double grow_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const TriangleMesh& mesh = *scene.meshes.front().mesh;  // the tubes
    const StrandStats& st = strands.stats;
    // Counts only: the file is the same bytes for any thread count (timings go to --stats).
    const nlohmann::json counts = {{"name", system.name},
                                   {"seeded", st.seeded},
                                   {"strands", strands.size()},
                                   {"points", strands.points.size()},
                                   {"moves", st.moves},
                                   {"collisions", st.collisions},
                                   {"cutter_hits", st.cutter_hits},
                                   {"splits", st.splits},
                                   {"killed", st.killed},
                                   {"dropped", st.dropped},
                                   {"solid_hits", st.solid_hits},
                                   {"crowded", st.crowded},
                                   {"triangles", mesh.triangleCount()}};
    scene.scene_extras_json = nlohmann::json{{"particles", counts}}.dump();
    if (!writeSceneGltf(out, scene, &error)) return fail(error);
    if (args.has("--stats")) {
        nlohmann::json stats = counts;
        stats["grow_seconds"] = grow_seconds;
        stats["threads"] = threads;
        if (!writeTextFileAtomically(args.get("--stats"), stats.dump(2) + "\n", &error)) return fail(error);
    }
    std::printf("%zu strands (%zu points, %llu moves, %llu refused by collisions) grown and meshed in %.3f s, %zu triangles -> %s\n",
                strands.size(), strands.points.size(), static_cast<unsigned long long>(st.moves),
                static_cast<unsigned long long>(st.collisions), grow_seconds, mesh.triangleCount(), out.c_str());
    return 0;
}

}  // namespace ug::cli
