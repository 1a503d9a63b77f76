// Pieces the model readers (mesh_readers.h) share: a line-aware text scanner over a byte buffer,
// number parsing without iostreams or allocation, error text, and the common finish (limits,
// validateMesh, normals). Internal to engine/mesh; not a public interface.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "mesh/triangle_mesh.h"

namespace ug::mesh_reader {

// Sets *error to "<name>: <why>" and returns false.
bool fail(std::string* error, const std::string& name, const std::string& why);

// A token as it may appear in a message: quoted, at most 40 characters, unprintable bytes shown as
// '?', so garbage input cannot flood or corrupt the message.
std::string shown(std::string_view token);

// "nan", "inf", "-inf" or the value, for messages about binary coordinates.
std::string valueText(double value);

// The text without a leading UTF-8 byte order mark, which Windows tools like to write.
inline std::string_view withoutBom(std::string_view text) {
    return text.substr(0, 3) == "\xEF\xBB\xBF" ? text.substr(3) : text;
}

// "x", "y" or "z" for axis 0, 1, 2.
inline std::string axisName(int axis) {
    return std::string(1, "xyz"[axis]);
}

// Strict parses of a whole token (a leading '+' is allowed). parseReal accepts what strtod does in
// the "C" locale, including nan and inf (the caller decides whether those are errors); magnitudes
// beyond double range become +-inf and tiny ones 0 or a denormal, like strtod.
bool parseReal(std::string_view token, double* value);
bool parseInteger(std::string_view token, int64_t* value);

// Walks text one token at a time, counting lines. Tokens are separated by blanks (space, tab, \r, \v,
// \f) and line ends; `comment` (0 for none) starts a comment that runs to the end of the line; with
// `continuation`, a '\' before the line end joins the next line (OBJ). Every call consumes input or
// reports the end, so loops over it terminate.
class TextScanner {
  public:
    // `first_line`: the number of the text's first line, for a text that starts inside a file.
    TextScanner(std::string_view text, char comment, bool continuation, size_t first_line = 1)
        : text_(text), line_(first_line), comment_(comment), continuation_(continuation) {}

    bool atEnd() const { return pos_ >= text_.size(); }
    size_t line() const { return line_; }   // 1-based line of the next unread byte
    size_t offset() const { return pos_; }  // bytes consumed so far
    size_t remaining() const { return text_.size() - pos_; }

    // The next token on the current line; empty at the end of the line or the text (the line end
    // itself is not consumed).
    std::string_view lineToken();
    // The next token, crossing line ends; empty only at the end of the text.
    std::string_view token();
    // Skips the rest of the current line, including its line end.
    void nextLine();
    // Moves to the start of the next line that has a token (skipping blank and comment-only lines).
    // False at the end of the text.
    bool nextContentLine();

  private:
    void skipBlanks();
    bool isSeparator(char c) const;

    std::string_view text_;
    size_t pos_ = 0;
    size_t line_;
    char comment_;
    bool continuation_;
};

// "declares 1099511627776 vertices but the file has only 100 bytes" when `count` elements of at least
// `min_bytes` each cannot fit in `available` bytes (overflow-safe); empty when they can.
std::string countExceedsFile(uint64_t count, uint64_t min_bytes, uint64_t available, const std::string& what,
                             uint64_t file_size);

// "...: models are limited to 50000000 vertices (kMaxMeshVertices)" style checks; empty when within.
std::string vertexLimitExceeded(uint64_t count);
std::string triangleLimitExceeded(uint64_t count);

// The readers' common end: limits, validateMesh (a backstop: the readers check elements as they go,
// with better messages), "no triangles", computeNormals, then moves `mesh` into *out.
bool finish(TriangleMesh* mesh, const std::string& name, TriangleMesh* out, std::string* error);

}  // namespace ug::mesh_reader
