// Optional: the fuzz targets as libFuzzer entry points, for coverage-guided runs on a developer machine
// (CI uses fuzz_inputs, GCC only). Built when UG_LIBFUZZER=ON, which needs clang (Debian 12: clang-14,
// libclang-rt-14-dev) and UG_SANITIZE=ON:
//   CC=clang-14 CXX=clang++-14 cmake -S . -B build-libfuzzer -DUG_SANITIZE=ON -DUG_LIBFUZZER=ON -DUG_BUILD_APP=OFF
//   cmake --build build-libfuzzer --target fuzz_libfuzzer_ply
//   build-libfuzzer/tests/fuzz_libfuzzer_ply -max_total_time=60 corpus-copy/ tests/fuzz/corpus/ply
// One binary per target (UG_FUZZ_TARGET). The checks are fuzz_inputs' (fuzz_targets.cpp): a broken promise
// or a rejection message that does not name the file aborts, which libFuzzer reports as a crash. libFuzzer
// mutates on its own (our format-aware mutations are fuzz_inputs'); the forged target still gets its
// checksum repaired before each run.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "fuzz.h"

namespace {

const ug::fuzz::Target* target = nullptr;
std::string input_path;

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    namespace fs = std::filesystem;
    target = ug::fuzz::findTarget(UG_FUZZ_TARGET);
    if (!target) std::abort();
    // The scene's models and the .gltf's external buffer, next to the input as fuzz_inputs puts them.
    const fs::path dir = fs::temp_directory_path() / ("ug-libfuzzer-" + std::string(target->name) + "-" +
                                                      std::to_string(getpid()));
    fs::create_directories(dir);
    const fs::path data = fs::path(UG_FUZZ_CORPUS_DIR) / (target->corpus ? target->corpus : target->name) / "data";
    if (fs::is_directory(data)) fs::copy(data, dir / "data", fs::copy_options::recursive);
    input_path = (dir / ((std::string(target->name) == "scene" ? "scene" : "input") + std::string(target->ext))).string();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::string bytes(reinterpret_cast<const char*>(data), size);
    if (target->fixup) target->fixup(&bytes);  // ghosttile-forged: the payload's size and checksum
    ug::fuzz::writeFile(input_path, bytes);
    const ug::fuzz::Outcome o = target->run(input_path);
    if (!o.violation.empty()) {
        std::fprintf(stderr, "broken promise: %s\n", o.violation.c_str());
        std::abort();
    }
    if (!o.accepted) {
        const std::string bad = ug::fuzz::checkMessage(*target, input_path, o.message);
        if (!bad.empty()) {
            std::fprintf(stderr, "bad message: %s: '%s'\n", bad.c_str(), o.message.c_str());
            std::abort();
        }
    }
    return 0;
}
