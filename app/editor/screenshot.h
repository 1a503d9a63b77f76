// Pictures to disk: the editor's screenshots (viewer.cpp) and `undergrowth render` write the same PNGs.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace ug::editor {

// `rgba`: width x height RGBA8 pixels, rows top-down. Written as an 8-bit RGB PNG (alpha dropped: the
// default framebuffer of a 24-bit visual has none worth keeping); the parent folder is created.
bool writeScreenshot(const std::string& path, int width, int height, const std::vector<uint8_t>& rgba,
                     std::string* error);

}  // namespace ug::editor
