// Deterministic mutations. Every choice comes from an Rng seeded by hashWords(seed, target, index), so
// an input is reproducible from its index; nothing here reads the clock or global state.
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/hash.h"
#include "fuzz.h"

namespace ug::fuzz {

uint64_t Rng::next() {
    state_ += 0x9e3779b97f4a7c15ull;
    return mix64(state_);
}

size_t Rng::below(size_t n) { return size_t(next() % uint64_t(n)); }

std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot read");
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

void writeFile(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    if (!out.flush()) throw std::runtime_error(path + ": cannot write");
}

bool loadCorpus(const std::string& dir, Corpus* out, std::string* error) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) {
        *error = dir + ": no such corpus folder";
        return false;
    }
    Corpus c;
    c.dir = dir;
    for (const auto& e : fs::directory_iterator(dir)) {
        if (e.is_regular_file()) c.names.push_back(e.path().filename().string());
        else if (e.is_directory() && e.path().filename() == "data") c.data_dir = e.path().string();
    }
    std::sort(c.names.begin(), c.names.end());
    for (const std::string& n : c.names) c.files.push_back(readFile((fs::path(dir) / n).string()));
    if (c.files.empty()) {
        *error = dir + ": the corpus folder has no seed files";
        return false;
    }
    *out = std::move(c);
    return true;
}

namespace {

// Values that sit on the edges readers get wrong: sizes, signs, float specials, overflow of every width.
const char* const kNumberTokens[] = {
    "1e400", "-1e400", "1e-400", "-1", "0", "-0", "nan", "NaN", "inf", "-inf", "4294967296", "4294967295",
    "2147483648", "-2147483649", "18446744073709551616", "18446744073709551615", "9223372036854775808",
    "65536", "65535", "16385", "1e9", "3.5e38", "1e38", "1e-45", "0.0", "1.", ".5", "5e", "--1", "1e+", "0x10",
};

std::string fourHundredDigits() {
    std::string s = "1";
    s.append(399, '7');
    return s;
}

bool isDigit(char c) { return c >= '0' && c <= '9'; }
bool isWordChar(char c) {
    return isDigit(c) || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || c == '.';
}

// [begin, end) of every number token: digits with an optional sign, fraction and exponent, not glued to
// a word ("v2" or "x86" are not numbers).
std::vector<std::pair<size_t, size_t>> numberTokens(const std::string& s) {
    std::vector<std::pair<size_t, size_t>> tokens;
    size_t i = 0;
    while (i < s.size() && tokens.size() < 100000) {
        const bool sign = (s[i] == '-' || s[i] == '+') && i + 1 < s.size() && (isDigit(s[i + 1]) || s[i + 1] == '.');
        if ((isDigit(s[i]) || sign) && (i == 0 || !isWordChar(s[i - 1]))) {
            size_t j = i + (sign ? 1 : 0);
            while (j < s.size() && (isDigit(s[j]) || s[j] == '.')) ++j;
            if (j < s.size() && (s[j] == 'e' || s[j] == 'E')) {
                size_t k = j + 1;
                if (k < s.size() && (s[k] == '-' || s[k] == '+')) ++k;
                if (k < s.size() && isDigit(s[k])) {
                    j = k;
                    while (j < s.size() && isDigit(s[j])) ++j;
                }
            }
            tokens.emplace_back(i, j);
            i = j;
        } else {
            ++i;
        }
    }
    return tokens;
}

void flipBit(std::string* b, Rng& rng) {
    if (b->empty()) return;
    (*b)[rng.below(b->size())] ^= char(1u << rng.below(8));
}

void setInterestingByte(std::string* b, Rng& rng) {
    static const unsigned char kBytes[] = {0x00, 0x01, 0x7f, 0x80, 0xff, 0xfe, '0', '9', '-', '.', 'e', ' ',
                                           '\n', '"', '{', '}', '[', ']', ',', ':', '\\', '/'};
    if (b->empty()) return;
    (*b)[rng.below(b->size())] = char(kBytes[rng.below(sizeof(kBytes))]);
}

void setRandomByte(std::string* b, Rng& rng) {
    if (b->empty()) return;
    (*b)[rng.below(b->size())] = char(rng.next());
}

// A 1-, 2-, 4- or 8-byte integer written over the bytes at a random offset, little- or big-endian:
// binary headers hide counts and sizes in such words.
void setInterestingWord(std::string* b, Rng& rng) {
    static const int kWidths[] = {1, 2, 4, 8};
    const int w = kWidths[rng.below(4)];
    if (b->size() < size_t(w)) return;
    uint64_t v = interestingCount(rng.below(300), rng);
    if (rng.oneIn(4)) v = ~v + 1;  // negative
    const size_t at = rng.below(b->size() - size_t(w) + 1);
    const bool big = rng.oneIn(3);
    for (int k = 0; k < w; ++k) (*b)[at + size_t(k)] = char(v >> (8 * (big ? w - 1 - k : k)));
}

void insertBytes(std::string* b, Rng& rng) {
    const size_t at = rng.below(b->size() + 1);
    const size_t n = 1 + rng.below(rng.oneIn(4) ? 256 : 8);
    std::string ins(n, '\0');
    const bool repeat = rng.oneIn(2);
    const char fill = char(rng.next());
    for (char& c : ins) c = repeat ? fill : char(rng.next());
    b->insert(at, ins);
}

void deleteRange(std::string* b, Rng& rng) {
    if (b->empty()) return;
    const size_t at = rng.below(b->size());
    const size_t n = 1 + rng.below(std::min<size_t>(b->size() - at, rng.oneIn(4) ? 1024 : 16));
    b->erase(at, n);
}

// A range copied elsewhere (or right after itself): repeats a record, a JSON member, an "f" line.
void duplicateRange(std::string* b, Rng& rng) {
    if (b->empty()) return;
    const size_t at = rng.below(b->size());
    const size_t n = 1 + rng.below(std::min<size_t>(b->size() - at, rng.oneIn(4) ? 2048 : 64));
    const std::string piece = b->substr(at, n);
    const size_t to = rng.oneIn(2) ? at + n : rng.below(b->size() + 1);
    const int times = rng.oneIn(8) ? 1 + int(rng.below(16)) : 1;
    for (int k = 0; k < times; ++k) b->insert(to, piece);
}

void truncate(std::string* b, Rng& rng) {
    if (b->empty()) return;
    b->resize(rng.below(b->size()));
}

// Crossing over with another seed: this one's head, the other's tail (or a piece of the other inserted).
void splice(std::string* b, Rng& rng, const Corpus* corpus, size_t keep_prefix) {
    if (!corpus || corpus->files.empty()) return;
    std::string other = corpus->files[rng.below(corpus->files.size())];
    other = other.size() > keep_prefix ? other.substr(keep_prefix) : std::string();
    if (other.empty()) return;
    const size_t cut_here = rng.below(b->size() + 1);
    const size_t cut_there = rng.below(other.size());
    if (rng.oneIn(2)) {
        b->resize(cut_here);
        b->append(other, cut_there);
    } else {
        const size_t n = 1 + rng.below(std::min<size_t>(other.size() - cut_there, 512));
        b->insert(cut_here, other, cut_there, n);
    }
}

}  // namespace

uint64_t interestingCount(uint64_t n, Rng& rng) {
    switch (rng.below(16)) {
        case 0: return 0;
        case 1: return 1;
        case 2: return n ? n - 1 : 0;
        case 3: return n + 1;
        case 4: return n * 2;
        case 5: return 65535;
        case 6: return 65536;
        case 7: return 0x7fffffffull;
        case 8: return 0x80000000ull;
        case 9: return 0xffffffffull;
        case 10: return 0x100000000ull;
        case 11: return ~uint64_t(0);
        case 12: return 1ull << 20;
        case 13: return 16385;
        case 14: return n * 1000;
        default: return n + 1 + rng.below(16);
    }
}

bool replaceNumberToken(std::string* b, Rng& rng) {
    const auto tokens = numberTokens(*b);
    if (tokens.empty()) return false;
    const auto [begin, end] = tokens[rng.below(tokens.size())];
    std::string with;
    const size_t pick = rng.below(std::size(kNumberTokens) + 3);
    if (pick < std::size(kNumberTokens)) with = kNumberTokens[pick];
    else if (pick == std::size(kNumberTokens)) with = fourHundredDigits();
    else with = std::to_string(interestingCount(std::strtoull(b->c_str() + begin, nullptr, 10), rng));
    b->replace(begin, end - begin, with);
    return true;
}

bool bumpCountAfter(std::string* b, Rng& rng, const std::vector<std::string>& keys) {
    // Every occurrence of every key, then one chosen: a format's counts are few, and all are worth a try.
    std::vector<size_t> at;
    for (const std::string& k : keys)
        for (size_t p = b->find(k); p != std::string::npos && at.size() < 4096; p = b->find(k, p + 1))
            at.push_back(p + k.size());
    if (at.empty()) return false;
    // The number follows the key on its line, after a few separators ("count": 12, element vertex 12).
    size_t p = at[rng.below(at.size())];
    const size_t limit = std::min(b->size(), p + 32);
    while (p < limit && !isDigit((*b)[p]) && (*b)[p] != '-' && (*b)[p] != '\n') ++p;
    if (p >= limit || (*b)[p] == '\n') return false;
    size_t e = p;
    while (e < b->size() && (isDigit((*b)[e]) || (*b)[e] == '-')) ++e;
    if (e == p) return false;
    const uint64_t old = std::strtoull(b->c_str() + p, nullptr, 10);
    b->replace(p, e - p, std::to_string(interestingCount(old, rng)));
    return true;
}

void mutateGeneric(std::string* b, Rng& rng, const Corpus* corpus, size_t keep_prefix) {
    switch (rng.below(12)) {
        case 0: flipBit(b, rng); break;
        case 1: setInterestingByte(b, rng); break;
        case 2: setRandomByte(b, rng); break;
        case 3: setInterestingWord(b, rng); break;
        case 4: insertBytes(b, rng); break;
        case 5: deleteRange(b, rng); break;
        case 6: duplicateRange(b, rng); break;
        case 7: truncate(b, rng); break;
        case 8: splice(b, rng, corpus, keep_prefix); break;
        default:
            // Numbers are where text formats hide their sizes and ranges: weighted up.
            if (!replaceNumberToken(b, rng)) flipBit(b, rng);
            break;
    }
}

std::string makeInput(const Target& target, const Corpus& corpus, uint64_t seed, uint64_t index) {
    if (index < corpus.files.size()) return corpus.files[index];
    uint64_t name_hash = 0;
    for (const char* p = target.name; *p; ++p) name_hash = hashWords(name_hash, uint64_t(uint8_t(*p)));
    Rng rng(hashWords(seed, name_hash, index));
    const std::string& base = corpus.files[rng.below(corpus.files.size())];
    const size_t keep = std::min(target.keep_prefix, base.size());
    std::string body = base.substr(keep);
    // Mostly one or two edits (near-valid inputs reach deep code), sometimes a pile of them.
    const int edits = rng.oneIn(2) ? 1 : rng.oneIn(2) ? 2 : 1 + int(rng.below(8));
    for (int k = 0; k < edits; ++k) {
        bool done = false;
        if (!target.mutators.empty() && rng.oneIn(3))
            done = target.mutators[rng.below(target.mutators.size())](&body, rng);
        if (!done) mutateGeneric(&body, rng, &corpus, keep);
        // Stacked duplications could grow without bound; real inputs of interest are small.
        if (body.size() > (size_t(1) << 20)) body.resize(size_t(1) << 20);
    }
    std::string input = base.substr(0, keep) + body;
    if (target.fixup) target.fixup(&input);
    return input;
}

}  // namespace ug::fuzz
