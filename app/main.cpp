// undergrowth: one binary for the headless CLI (batch jobs, benchmarks) and the editor.
#include <cstdio>
#include <cstring>
#include <string>

#include "cli/commands.h"

namespace {

void printUsage() {
    std::printf(
        "Undergrowth — entangled details for natural scenes\n"
        "\n"
        "usage:\n"
        "  undergrowth run [SCENE] [--out DIR] [--threads N] [--headless] [--frames N] [--screenshot OUT.png]\n"
        "      SCENE (default: the bundled assets/scenes/default.json) in the editor when a display is there;\n"
        "      without one, or with --headless, the main job: the scene, its statistics, a tile preview and the\n"
        "      Ghost Tile cache under DIR (default: out); --frames/--screenshot: a scripted editor run (as edit)\n"
        "  undergrowth instantiate SCENE -o OUT.glb|OUT.gltf [--stats FILE] [--seed N] [--threads N]\n"
        "                          [--region xmin,ymin,zmin,xmax,ymax,zmax] [--plain-nodes] [--chunk M] [--cache DIR]\n"
        "                          [--measure]\n"
        "      instantiate the scene (or one region of it) headless, settle it, and export glTF 2.0 with\n"
        "      EXT_mesh_gpu_instancing (--plain-nodes: one node per instance); --stats writes the statistics,\n"
        "      with --measure also how instances rest and whether the tile shows (measurements)\n"
        "  undergrowth edit SCENE [--frames N] [--screenshot OUT.png] [--stats STATS.json] [--size WxH]\n"
        "                   [--threads N] [--cache DIR] [--config DIR] [--replay SCRIPT.json] [--recover yes|no]\n"
        "                   [--autosave-interval SECONDS] [--no-shadows] [--no-ao]\n"
        "      open the editor's window on SCENE (needs a display; exit 1 without one); --replay runs a script of\n"
        "      tool actions; --frames N then renders N frames once the script is done and the instances settled,\n"
        "      writes the screenshot and statistics, and exits\n"
        "  undergrowth render SCENE -o PICTURE.png [--camera tx,ty,tz,distance,yaw_deg,pitch_deg] [--size WxH]\n"
        "                     [--threads N] [--cache DIR] [--no-shadows] [--no-ao] [--frames N]\n"
        "                     [--particles PARTICLES.json]\n"
        "      a picture of the settled scene from the editor's opening view (or --camera), without any display\n"
        "      (EGL); --size defaults to 1280x720; --frames N times N frames (median); --particles draws a\n"
        "      particle system's strands into it\n"
        "  undergrowth environment SCENE --at x,y,z [--at x,y,z ...]\n"
        "      the environment at world points (snow, icicles, leaves, grass, trash, occlusion, humidity,\n"
        "      temperature, the shelter) and the terrain's height under them as JSON\n"
        "  undergrowth instantiate --plan DIR --task I [--threads N]\n"
        "      one task of a plan: region I, written atomically under DIR/regions (skipped when already complete)\n"
        "  undergrowth plan SCENE --out DIR [--memory-per-job BYTES] [--max-jobs N] [--threads-per-task N]\n"
        "                   [--seed N] [--binary PATH]\n"
        "      cut the world into region jobs sized by the memory budget: DIR/plan.json and the Slurm scripts\n"
        "      (DIR/submit.sh submits the Ghost Tile step, the job array and the join)\n"
        "  undergrowth join DIR [-o WORLD.glb] [--max-bytes BYTES]\n"
        "      check every region of the plan is there and from the plan; DIR/manifest.json and, when it fits,\n"
        "      the joined world\n"
        "  undergrowth grow PARTICLES.json -o OUT.glb [--stats FILE] [--threads N]\n"
        "      particle sculpting: grow a particle system's strands and write them as tubes (docs/particles.md)\n"
        "  undergrowth build-tile SCENE [--cache DIR] [--stats FILE] [--threads N]\n"
        "      build (or load from the verified cache) the scene's Ghost Tile and print its statistics\n"
        "  undergrowth bench [--quick] [--json FILE] [--threads N] [--filter NAME]\n"
        "      benchmarks: prints a table; --json writes {\"results\": [...]}\n"
        "  undergrowth make-assets [--out DIR] [--env-out DIR]\n"
        "      regenerate the procedural starter models (assets/models/*.glb, assets/env_models/*.glb)\n"
        "  undergrowth --help | --version\n"
        "\n"
        "exit codes: 0 success, 1 the job failed (the message names the file and the reason), 2 bad usage\n");
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) return ug::cli::runMainJob(argc, argv);
    const std::string command = argv[1];
    if (command == "run") return ug::cli::runMainJob(argc, argv);
    if (command == "instantiate") return ug::cli::runInstantiateCommand(argc, argv);
    if (command == "edit") return ug::cli::runEditCommand(argc, argv);
    if (command == "render") return ug::cli::runRenderCommand(argc, argv);
    if (command == "environment") return ug::cli::runEnvironmentCommand(argc, argv);
    if (command == "build-tile") return ug::cli::runBuildTileCommand(argc, argv);
    if (command == "bench") return ug::cli::runBenchCommand(argc, argv);
    if (command == "plan") return ug::cli::runPlanCommand(argc, argv);
    if (command == "join") return ug::cli::runJoinCommand(argc, argv);
    if (command == "grow") return ug::cli::runGrowCommand(argc, argv);
    if (command == "make-assets") return ug::cli::runMakeAssetsCommand(argc, argv);
    if (command == "--help" || command == "-h" || command == "help") {
        printUsage();
        return 0;
    }
    if (command == "--version") {
        std::printf("undergrowth 0.1.0\n");
        return 0;
    }
    std::fprintf(stderr, "undergrowth: unknown command '%s' (try --help)\n", command.c_str());
    return 2;
}
