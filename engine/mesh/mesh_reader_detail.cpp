// Shared reader pieces (mesh_reader_detail.h) and readMeshFileBytes (mesh_readers.h).
#include "mesh/mesh_reader_detail.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "core/atomic_file.h"
#include "mesh/mesh_readers.h"

namespace ug {

bool readMeshFileBytes(const std::string& path, std::vector<unsigned char>* bytes, std::string* error) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (ec || !fs::exists(status)) return mesh_reader::fail(error, path, "no such file");
    if (!fs::is_regular_file(status)) return mesh_reader::fail(error, path, "not a regular file");
    const uintmax_t size = fs::file_size(path, ec);
    if (ec) return mesh_reader::fail(error, path, "cannot read the file size: " + ec.message());
    // Checked here, before any byte is read, so an oversized file costs nothing; readWholeFile checks
    // again on the open file in case it grew in between.
    if (size > kMaxMeshFileBytes)
        return mesh_reader::fail(error, path,
                                 "the file has " + std::to_string(size) +
                                     " bytes; model files are limited to " +
                                     std::to_string(kMaxMeshFileBytes) + " bytes (2 GiB, kMaxMeshFileBytes)");
    return readWholeFile(path, bytes, error, size_t(kMaxMeshFileBytes));
}

}  // namespace ug

namespace ug::mesh_reader {

bool fail(std::string* error, const std::string& name, const std::string& why) {
    if (error) *error = name + ": " + why;
    return false;
}

std::string shown(std::string_view token) {
    constexpr size_t kMaxShown = 40;
    std::string text = "'";
    for (size_t i = 0; i < token.size() && i < kMaxShown; ++i) {
        const unsigned char c = static_cast<unsigned char>(token[i]);
        text += (c >= 0x20 && c < 0x7f) ? char(c) : '?';
    }
    if (token.size() > kMaxShown) text += "...";
    return text + "'";
}

std::string valueText(double value) {
    if (std::isnan(value)) return "nan";
    if (std::isinf(value)) return value < 0 ? "-inf" : "inf";
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", value);
    return buffer;
}

namespace {

// from_chars takes '-' but not '+'; files do write "+1.5". False for an empty token or a second sign.
bool stripPlus(std::string_view* token) {
    if (!token->empty() && token->front() == '+') {
        token->remove_prefix(1);
        if (!token->empty() && (token->front() == '+' || token->front() == '-')) return false;
    }
    return !token->empty();
}

}  // namespace

bool parseReal(std::string_view token, double* value) {
    if (!stripPlus(&token)) return false;
    const char* end = token.data() + token.size();
    const auto [ptr, ec] = std::from_chars(token.data(), end, *value, std::chars_format::general);
    if (ptr != end) return false;
    if (ec == std::errc()) return true;
    if (ec != std::errc::result_out_of_range) return false;
    // from_chars leaves the value unset when it over- or underflows; strtod gives the conventional
    // +-HUGE_VAL or a tiny value, which the callers then judge. Rare, so the copy does not matter.
    const std::string copy(token);
    *value = std::strtod(copy.c_str(), nullptr);
    return true;
}

bool parseInteger(std::string_view token, int64_t* value) {
    if (!stripPlus(&token)) return false;
    const char* end = token.data() + token.size();
    const auto [ptr, ec] = std::from_chars(token.data(), end, *value);
    return ec == std::errc() && ptr == end;
}

bool TextScanner::isSeparator(char c) const {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f' ||
           (comment_ != 0 && c == comment_) || (continuation_ && c == '\\');
}

void TextScanner::skipBlanks() {
    const size_t n = text_.size();
    while (pos_ < n) {
        const char c = text_[pos_];
        if (c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f') {
            ++pos_;
        } else if (comment_ != 0 && c == comment_) {
            const size_t eol = text_.find('\n', pos_);
            pos_ = eol == std::string_view::npos ? n : eol;  // the line end stays for the caller
        } else if (continuation_ && c == '\\') {
            // A '\' followed (after blanks) by the line end joins the next line; a stray one is a blank.
            size_t p = pos_ + 1;
            while (p < n && (text_[p] == ' ' || text_[p] == '\t' || text_[p] == '\r')) ++p;
            if (p < n && text_[p] == '\n') {
                pos_ = p + 1;
                ++line_;
            } else {
                pos_ = p;
            }
        } else {
            break;
        }
    }
}

std::string_view TextScanner::lineToken() {
    skipBlanks();
    const size_t start = pos_, n = text_.size();
    while (pos_ < n && !isSeparator(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
}

std::string_view TextScanner::token() {
    for (;;) {
        const std::string_view t = lineToken();
        if (!t.empty() || atEnd()) return t;
        ++pos_;  // lineToken stopped at a '\n'
        ++line_;
    }
}

void TextScanner::nextLine() {
    const size_t eol = text_.find('\n', pos_);
    if (eol == std::string_view::npos) {
        pos_ = text_.size();
    } else {
        pos_ = eol + 1;
        ++line_;
    }
}

bool TextScanner::nextContentLine() {
    for (;;) {
        skipBlanks();
        if (atEnd()) return false;
        if (text_[pos_] != '\n') return true;
        ++pos_;
        ++line_;
    }
}

std::string countExceedsFile(uint64_t count, uint64_t min_bytes, uint64_t available, const std::string& what,
                             uint64_t file_size) {
    if (min_bytes == 0 || count <= available / min_bytes) return {};
    return "declares " + std::to_string(count) + " " + what + " but the file has only " +
           std::to_string(file_size) + " bytes";
}

std::string vertexLimitExceeded(uint64_t count) {
    if (count <= kMaxMeshVertices) return {};
    return std::to_string(count) + " vertices; models are limited to " + std::to_string(kMaxMeshVertices) +
           " vertices (kMaxMeshVertices)";
}

std::string triangleLimitExceeded(uint64_t count) {
    if (count <= kMaxMeshTriangles) return {};
    return std::to_string(count) + " triangles; models are limited to " + std::to_string(kMaxMeshTriangles) +
           " triangles (kMaxMeshTriangles)";
}

bool finish(TriangleMesh* mesh, const std::string& name, TriangleMesh* out, std::string* error) {
    if (mesh->indices.empty()) return fail(error, name, "no triangles");
    std::string why = vertexLimitExceeded(mesh->positions.size());
    if (why.empty()) why = triangleLimitExceeded(mesh->triangleCount());
    if (!why.empty()) return fail(error, name, "the model has " + why);
    if (!validateMesh(*mesh, &why)) return fail(error, name, why);
    computeNormals(mesh);
    *out = std::move(*mesh);
    return true;
}

}  // namespace ug::mesh_reader
