// Parsing a JSON document from a user's file without letting the JSON library's exceptions escape.
// nlohmann::json throws on syntax errors (with a line and column) but also on numbers it cannot hold
// ("1e400", a 400-digit integer: out_of_range.406, with no position at all). Both become located messages:
//   "<source>: invalid JSON at line L, column C (in <JSON Pointer>): <what is wrong>"
//   "<source>: <JSON Pointer>: number 1e400 is out of range (larger than a double can hold) (line L, column C)"
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace ug {

// Parses `text` (named `source` in messages). Returns false with the located reason on any error.
bool parseJsonText(const std::string& text, const std::string& source, nlohmann::json* out, std::string* error);

}  // namespace ug
