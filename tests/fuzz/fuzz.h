// The pieces of the fuzz harness shared by its files. fuzz_inputs.cpp's top comment is the manual;
// fuzz_mutate.cpp makes the inputs, fuzz_targets.cpp runs them through the readers, fuzz_runner.cpp
// forks, watches and records, fuzz_corpus.cpp writes the committed seed corpus.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace ug::fuzz {

// Counter-based like every random number in Undergrowth: input i of a run is a pure function of
// (seed, target, i, corpus), so the parent process can rebuild the input a child crashed on without
// asking the (dead) child, and a finding reproduces from its index alone.
class Rng {
public:
    explicit Rng(uint64_t seed) : state_(seed) {}
    uint64_t next();
    size_t below(size_t n);  // in [0, n); n > 0
    bool oneIn(unsigned n) { return below(n) == 0; }

private:
    uint64_t state_;
};

// The seeds of one target: the regular files directly in its corpus folder (sorted by name, so input
// numbering does not depend on the file system's order). A sub-folder "data/" holds files the seeds
// refer to by relative path (the scene's models and terrain, a .gltf's external buffer); it is copied
// next to every input and never mutated.
struct Corpus {
    std::string dir;
    std::vector<std::string> names;
    std::vector<std::string> files;
    std::string data_dir;  // empty when there is none
};
bool loadCorpus(const std::string& dir, Corpus* out, std::string* error);

// What a reader did with one input. A rejection with a message is the expected result for most inputs.
struct Outcome {
    bool accepted = false;
    std::string message;    // the reader's error when rejected
    std::string violation;  // non-empty: the result broke a promise of the reader's header (a finding)
};

// A format-aware mutation: edits *bytes in place, returns false when it found nothing to edit (the
// caller then falls back to a generic mutation).
using FormatMutator = bool (*)(std::string* bytes, Rng& rng);

struct Target {
    const char* name;
    const char* ext;   // the input file's extension: loadMeshFile dispatches on it
    const char* what;  // one line for --list
    Outcome (*run)(const std::string& path);
    std::vector<FormatMutator> mutators;
    // Forging: the first keep_prefix bytes (a header) are never mutated, the rest is, then fixup()
    // repairs what a careful forger would (the cache's payload size and checksum).
    size_t keep_prefix = 0;
    void (*fixup)(std::string* bytes) = nullptr;
    const char* corpus = nullptr;  // the corpus folder's name when it is another target's (default: name)
};

const std::vector<Target>& targets();
const Target* findTarget(const std::string& name);
// The rejection message must be non-empty and name the file: the input's path or, for a scene, a file
// in the scene's folder (a model or terrain it refers to). Returns the complaint, or "" when fine.
std::string checkMessage(const Target& target, const std::string& input_path, const std::string& message);

// Input `index` of a run. Indices below corpus.files.size() are the seeds themselves, unmutated, so
// every run first proves the corpus loads as its names say (valid seeds accepted, near-valid rejected).
std::string makeInput(const Target& target, const Corpus& corpus, uint64_t seed, uint64_t index);

// Generic byte-level mutations, also used inside format-aware ones (a GLB's JSON chunk).
void mutateGeneric(std::string* bytes, Rng& rng, const Corpus* corpus, size_t keep_prefix);
// Replaces one number token ("12", "-0.5", "3e2") with an interesting one: 1e400, -1, 0, nan,
// 4294967296, a 400-digit integer, ... Returns false when the text has no number.
bool replaceNumberToken(std::string* bytes, Rng& rng);
// Sets the number after one of `keys` ("count": 12 or "element vertex 12") to an interesting count.
bool bumpCountAfter(std::string* bytes, Rng& rng, const std::vector<std::string>& keys);
// An interesting count near `n`: 0, 1, n - 1, n + 1, 2n, 2^16, 2^31, 2^32 - 1, 2^32, 2^64 - 1, ...
uint64_t interestingCount(uint64_t n, Rng& rng);

// Writes the seed corpus (tests/fuzz/corpus) from shapes defined in fuzz_corpus.cpp.
int makeCorpus(const std::string& root);

// Small file helpers (errors are fatal: the harness's own files must work).
std::string readFile(const std::string& path);
void writeFile(const std::string& path, const std::string& bytes);

}  // namespace ug::fuzz
