// fuzz_inputs: bounded, deterministic fuzzing of every reader of hostile input (issue 16), in the
// repository and in CI, with GCC's AddressSanitizer + UndefinedBehaviorSanitizer (no clang needed).
//
//   fuzz_inputs TARGET[,TARGET...]|all [--corpus DIR] [--runs N] [--seconds S] [--seed K] [--out DIR]
//               [--keep-going] [--timeout S] [--rss-mb M] [--batch N] [--no-leak-check] [--save N]
//   fuzz_inputs TARGET --replay FILE... [--in-process]     run given files (findings) instead
//   fuzz_inputs TARGET --minimize FILE [--to OUT]           shrink a failing file (default OUT: FILE.min)
//   ... [--summary FILE]                                     also append the closing lines to FILE
//   fuzz_inputs --list                                       the targets
//   fuzz_inputs --make-corpus DIR                            rewrite the seed corpus (fuzz_corpus.cpp)
//
// Targets: scene (the CLI's scene load path: loadProject, the models, the Ghost Tile build, the terrain,
// compileScene), obj ply stl off glb gltf (loadMeshFile; the input gets the target's extension),
// ghosttile (the cache as found on disk) and ghosttile-forged (payload mutated, then its size and checksum
// recomputed the way a forger would, so mutations get past the checksum to the reader's own checks), png
// (loadHeightFieldPng), particles (loadParticleSystem; small systems are grown and meshed too). The corpus folder is DIR/<target> (DIR itself when it has no such sub-folder;
// default: the committed tests/fuzz/corpus). Its sub-folder data/ holds files the seeds refer to by
// relative path; it is copied next to each input, never mutated.
//
// Inputs: input i (i < number of seeds) is seed i unmutated; every later input is a seed with one to
// eight mutations chosen by a hash of (--seed, target, i): bit flips, interesting bytes and words, range
// insert / delete / duplicate, truncation, splicing two seeds, number tokens replaced by 1e400, -1, 0, nan,
// 4294967296, a 400-digit integer, ..., and per-format ones (header counts bumped, PLY without
// end_header, GLB JSON edited with its chunk lengths repaired, PNG pixels re-deflated, cache array counts
// set with or without their data, ...). So a run is reproducible and input i can be rebuilt from i.
// It stops after --runs inputs or --seconds, whichever comes first.
//
// Running: inputs run in-process in a forked child, a batch at a time (--batch); the parent watches.
// Failures, each one a finding:
//   crash      a signal, an ASan-caught SEGV / stack overflow, or an exception escaping the reader
//   hang       one input ran longer than --timeout (default 10 s); the child is stopped with SIGABRT so
//              a sanitized build prints where it was
//   sanitizer  an ASan / UBSan / LeakSanitizer report, including an allocation beyond
//              max_allocation_size_mb (2048 by default here, see __asan_default_options below)
//   memory     the child's resident memory went above --rss-mb (3000)
//   message    a rejection whose message is empty or does not name the file (for a scene: the scene or
//              a file in its folder)
//   promise    an accepted result that breaks its reader's header: a mesh failing validateMesh, a scene
//              whose saved form does not load back the same, a cache that saves to other bytes, ...
// Without --keep-going the first failure ends the target; with it, each failure is recorded and the next
// input runs. Failing inputs are saved under --out/<target>/<kind>-<index>.<ext> with the child's output
// (.log), at most --save per distinct finding (same kind and top stack frames); the first of each is
// printed with its top frames and the replay command. Rejections with a message are the expected result
// and are counted, not reported.
//
// Output: per target "fuzz TARGET: N inputs, C crashes, H hangs, S sanitizer reports, ...; R rejected
// with a message, A accepted (T s)" ("replay TARGET: ..." for --replay), then "P passed, F failed"
// (targets). Exit 0 when every target passed. --summary appends the per-target lines to a file as well:
// CTest shows the output of failed tests only, and CI prints the counts of every target from there.
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <sys/syscall.h>
#include <unistd.h>
#include <string>
#include <vector>

#include "fuzz.h"
#include "fuzz_runner.h"

// Memory bounds for every sanitized run, also when the environment sets no ASAN_OPTIONS (ASAN_OPTIONS
// still overrides single flags). allocator_may_return_null=0 makes an allocation above the limit a
// report with the allocating stack, rather than a bad_alloc a reader might swallow.
// symbolize=0 while fuzzing: llvm-symbolizer takes seconds per report, more than a thousand inputs, and
// a crash-prone reader reports often. Each new finding is replayed once in a fresh, symbolized process
// (fuzz_runner.cpp, rerunFresh); a --replay run is symbolized from the start. The command line is read
// from /proc because this runs before main, inside the sanitizer's start-up: plain system calls and
// loops only, no malloc, no intercepted functions.
// Not instrumented either: the shadow memory an instrumented access checks does not exist yet.
extern "C" __attribute__((no_sanitize("address", "undefined"))) const char* __asan_default_options() {
    static char cmdline[8192];
    ssize_t n = 0;
    // syscall(), not open(): the sanitizer's interceptors are not set up yet.
    const long fd = syscall(SYS_openat, AT_FDCWD, "/proc/self/cmdline", O_RDONLY);
    if (fd >= 0) {
        n = syscall(SYS_read, fd, cmdline, sizeof(cmdline) - 1);
        syscall(SYS_close, fd);
    }
    static const char kReplay[] = "--replay";
    bool replay = false;
    for (ssize_t k = 0; k < n;) {
        ssize_t e = k;
        while (e < n && cmdline[e]) ++e;
        bool same = e - k == ssize_t(sizeof(kReplay) - 1);
        for (ssize_t j = 0; same && j < e - k; ++j) same = cmdline[k + j] == kReplay[j];
        replay = replay || same;
        k = e + 1;
    }
    return replay ? "max_allocation_size_mb=2048:allocator_may_return_null=0:hard_rss_limit_mb=3000:handle_abort=1:"
                    "detect_leaks=1:symbolize=1"
                  : "max_allocation_size_mb=2048:allocator_may_return_null=0:hard_rss_limit_mb=3000:handle_abort=1:"
                    "detect_leaks=1:symbolize=0";
}
extern "C" const char* __ubsan_default_options() { return "print_stacktrace=1:halt_on_error=1"; }

namespace {

using namespace ug::fuzz;

int usage(const char* why) {
    std::fprintf(stderr, "fuzz_inputs: %s (see the top of tests/fuzz/fuzz_inputs.cpp)\n", why);
    return 2;
}

bool number(const char* s, double* out) {
    char* end = nullptr;
    *out = std::strtod(s, &end);
    return end != s && *end == '\0' && *out >= 0;
}

}  // namespace

int main(int argc, char** argv) {
    RunOptions options;
    options.self_path = argv[0];
    std::string corpus_root = UG_FUZZ_CORPUS_DIR;
    std::vector<std::string> names;
    std::string minimize_file, minimize_to, summary_file;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&](double* out) {
            if (i + 1 >= argc || !number(argv[i + 1], out)) return false;
            ++i;
            return true;
        };
        double v = 0;
        if (a == "--list") {
            for (const Target& t : targets()) std::printf("%-17s %s\n", t.name, t.what);
            return 0;
        } else if (a == "--make-corpus") {
            if (i + 1 >= argc) return usage("--make-corpus needs a folder");
            return makeCorpus(argv[i + 1]);
        } else if (a == "--corpus" && i + 1 < argc) {
            corpus_root = argv[++i];
        } else if (a == "--out" && i + 1 < argc) {
            options.out = argv[++i];
        } else if (a == "--runs" && value(&v)) {
            options.runs = uint64_t(v);
        } else if (a == "--seconds" && value(&v)) {
            options.seconds = v;
        } else if (a == "--seed" && value(&v)) {
            options.seed = uint64_t(v);
        } else if (a == "--timeout" && value(&v) && v > 0) {
            options.timeout_s = v;
        } else if (a == "--rss-mb" && value(&v) && v > 0) {
            options.rss_mb = uint64_t(v);
        } else if (a == "--batch" && value(&v) && v >= 1) {
            options.batch = uint64_t(v);
        } else if (a == "--save" && value(&v)) {
            options.save_per_finding = int(v);
        } else if (a == "--keep-going") {
            options.keep_going = true;
        } else if (a == "--no-leak-check") {
            options.leak_check = false;
        } else if (a == "--in-process") {
            options.in_process = true;
        } else if (a == "--work-dir" && i + 1 < argc) {
            options.work_dir = argv[++i];  // internal: the fresh-process replay of a finding (fuzz_runner.cpp)
        } else if (a == "--summary" && i + 1 < argc) {
            summary_file = argv[++i];
        } else if (a == "--minimize" && i + 1 < argc) {
            minimize_file = argv[++i];
        } else if (a == "--to" && i + 1 < argc) {
            minimize_to = argv[++i];
        } else if (a == "--replay") {
            while (i + 1 < argc && argv[i + 1][0] != '-') options.replay.push_back(argv[++i]);
            if (options.replay.empty()) return usage("--replay needs files");
        } else if (a.rfind("--", 0) == 0) {
            return usage(("unknown or incomplete option " + a).c_str());
        } else {
            // TARGET[,TARGET...] or all
            size_t p = 0;
            while (p <= a.size()) {
                const size_t e = std::min(a.find(',', p), a.size());
                const std::string n = a.substr(p, e - p);
                if (n == "all") {
                    for (const Target& t : targets()) names.push_back(t.name);
                } else if (!n.empty()) {
                    names.push_back(n);
                }
                p = e + 1;
            }
        }
    }
    if (names.empty()) return usage("no target given (--list shows them)");
    if (options.in_process && options.replay.empty()) return usage("--in-process only replays files");
    if (!options.replay.empty() && names.size() != 1) return usage("--replay takes exactly one target");
    if (!options.replay.empty()) options.keep_going = true;  // every given file is run
    if (!minimize_file.empty() && names.size() != 1) return usage("--minimize takes exactly one target");

    int passed = 0, failed = 0;
    std::string summary;
    for (const std::string& name : names) {
        const Target* target = findTarget(name);
        if (!target) return usage(("unknown target '" + name + "'").c_str());
        const std::filesystem::path sub = std::filesystem::path(corpus_root) / (target->corpus ? target->corpus : name);
        const std::string dir = std::filesystem::is_directory(sub) ? sub.string() : corpus_root;
        Corpus corpus;
        std::string error;
        if (!loadCorpus(dir, &corpus, &error)) {
            std::printf("fuzz %s: FAILED: %s\n", name.c_str(), error.c_str());
            ++failed;
            continue;
        }
        if (!minimize_file.empty())
            return minimize(*target, corpus, minimize_file, options,
                            minimize_to.empty() ? minimize_file + ".min" : minimize_to);
        const TargetResult r = fuzzTarget(*target, corpus, options);
        char line[1024];
        std::snprintf(line, sizeof(line),
                      "%s %s: %llu inputs, %llu crashes, %llu hangs, %llu sanitizer reports, %llu over memory, "
                      "%llu bad messages, %llu broken promises; %llu rejected with a message, %llu accepted "
                      "(%.1f s, slowest input %.2f s: #%llu)%s\n",
                      options.replay.empty() ? "fuzz" : "replay", name.c_str(), (unsigned long long)r.inputs,
                      (unsigned long long)r.crashes, (unsigned long long)r.hangs, (unsigned long long)r.sanitizer,
                      (unsigned long long)r.memory, (unsigned long long)r.messages, (unsigned long long)r.promises,
                      (unsigned long long)r.rejected, (unsigned long long)r.accepted, r.seconds, r.slowest_s,
                      (unsigned long long)r.slowest_index, r.passed() ? "" : " FAILED");
        summary += line;
        std::fputs(line, stdout);
        std::fflush(stdout);
        (r.passed() ? passed : failed)++;
    }
    std::printf("%d passed, %d failed\n", passed, failed);
    if (!summary_file.empty()) {
        // One write with O_APPEND: lines of targets running in parallel (ctest -j) do not interleave.
        const int fd = open(summary_file.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
        if (fd < 0 || write(fd, summary.data(), summary.size()) != ssize_t(summary.size())) {
            std::perror(summary_file.c_str());
            failed = std::max(failed, 1);
        }
        if (fd >= 0) close(fd);
    }
    return failed ? 1 : 0;
}
