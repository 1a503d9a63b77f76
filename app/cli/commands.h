// Subcommands of the undergrowth binary. Each returns the process exit code:
// 0 success, 1 failure of the job (bad input file, write error), 2 bad command line.
#pragma once

namespace ug::cli {

int runMainJob(int argc, char** argv);        // undergrowth run [SCENE] [--out DIR] [--threads N]
int runBuildTileCommand(int argc, char** argv);  // undergrowth build-tile SCENE [--cache DIR] [--stats FILE]
int runMakeAssetsCommand(int argc, char** argv);  // undergrowth make-assets [--out DIR]
int runBenchCommand(int argc, char** argv);      // undergrowth bench [--quick] [--json FILE]
int runInstantiateCommand(int argc, char** argv);  // undergrowth instantiate SCENE -o OUT.glb [...]
int runEditCommand(int argc, char** argv);       // undergrowth edit SCENE [--frames N] [--screenshot PNG] [...]

}  // namespace ug::cli
