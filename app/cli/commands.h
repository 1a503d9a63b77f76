// Subcommands of the undergrowth binary. Each returns the process exit code:
// 0 success, 1 failure of the job (bad input file, write error), 2 bad command line.
#pragma once

namespace ug::cli {

// undergrowth run [SCENE] [--out DIR] [--threads N] [--headless] [--frames N] [--screenshot PNG]: the editor
// on SCENE when a display is there (and not --headless), else the headless main job.
int runMainJob(int argc, char** argv);
int runBuildTileCommand(int argc, char** argv);  // undergrowth build-tile SCENE [--cache DIR] [--stats FILE]
int runMakeAssetsCommand(int argc, char** argv);  // undergrowth make-assets [--out DIR] [--env-out DIR]
int runBenchCommand(int argc, char** argv);      // undergrowth bench [--quick] [--json FILE]
int runPlanCommand(int argc, char** argv);       // undergrowth plan SCENE --out DIR [...]: region jobs (region_plan.h)
int runJoinCommand(int argc, char** argv);       // undergrowth join DIR [-o WORLD.glb]
int runGrowCommand(int argc, char** argv);       // undergrowth grow PARTICLES.json -o OUT.glb
int runInstantiateCommand(int argc, char** argv);  // undergrowth instantiate SCENE -o OUT.glb [...]
int runEditCommand(int argc, char** argv);       // undergrowth edit SCENE [--frames N] [--screenshot PNG] [...]
int runRenderCommand(int argc, char** argv);
// undergrowth environment SCENE --at x,y,z [--at ...]: the environment's channels and shelter as JSON
int runEnvironmentCommand(int argc, char** argv);     // undergrowth render SCENE -o PICTURE.png [...]: no display needed

}  // namespace ug::cli
