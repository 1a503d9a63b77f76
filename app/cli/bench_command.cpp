#include <cstdio>

#include "cli/bench.h"
#include "cli/cli_args.h"
#include "cli/commands.h"

namespace ug::cli {

int runBenchCommand(int argc, char** argv) {
    Args args;
    std::string error;
    if (!parseArgs(argc, argv, 2, {"--json", "--threads", "--filter", "--assets", "--cache"}, {"--quick"}, &args, &error)) {
        std::fprintf(stderr, "undergrowth bench: %s\n", error.c_str());
        return 2;
    }
    BenchContext ctx;
    ctx.quick = args.has("--quick");
    ctx.assets_dir = args.get("--assets", assetsDir());
    ctx.filter = args.get("--filter");
    ctx.cache_dir = args.get("--cache", ctx.cache_dir);
    if (args.has("--threads")) {
        long t;
        if (!parseInt("--threads", args.get("--threads"), 0, 256, &t, &error)) {
            std::fprintf(stderr, "undergrowth bench: %s\n", error.c_str());
            return 2;
        }
        ctx.threads = int(t);
    }
    struct Section {
        const char* name;
        bool (*run)(const BenchContext&, std::vector<BenchRow>*, std::string*);
    };
    const Section sections[] = {{"ghosttile", benchGhostTile},
                                {"instantiate", benchInstancer},
                                {"models", benchModels},
                                {"pile", benchPile},
                                {"env", benchEnvironment},
                                {"env_scatter", benchScatter},
                                {"particles", benchParticles},
                                {"world", benchWorld},
                                {"render", benchRender}};
    std::vector<BenchRow> rows;
    for (const Section& s : sections) {
        if (!ctx.filter.empty() && std::string(s.name).find(ctx.filter) == std::string::npos) continue;
        std::fprintf(stderr, "bench: %s%s\n", s.name, ctx.quick ? " (quick)" : "");
        if (!s.run(ctx, &rows, &error)) {
            std::fprintf(stderr, "undergrowth bench: section %s failed: %s\n", s.name, error.c_str());
            return 1;
        }
    }
    std::printf("%s", formatBenchTable(rows).c_str());
    if (args.has("--json")) {
        if (!writeBenchJson(args.get("--json"), rows, &error)) {
            std::fprintf(stderr, "undergrowth bench: %s\n", error.c_str());
            return 1;
        }
        std::fprintf(stderr, "bench: wrote %s\n", args.get("--json").c_str());
    }
    return 0;
}

}  // namespace ug::cli
