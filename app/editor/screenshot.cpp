#include "editor/screenshot.h"

#include <stb_image_write.h>

#include <filesystem>

namespace ug::editor {

bool writeScreenshot(const std::string& path, int width, int height, const std::vector<uint8_t>& rgba,
                     std::string* error) {
    std::vector<uint8_t> rgb(size_t(width) * size_t(height) * 3);
    for (size_t i = 0, n = size_t(width) * size_t(height); i < n; ++i) {
        rgb[i * 3 + 0] = rgba[i * 4 + 0];
        rgb[i * 3 + 1] = rgba[i * 4 + 1];
        rgb[i * 3 + 2] = rgba[i * 4 + 2];
    }
    std::error_code ec;
    const std::filesystem::path parent = std::filesystem::path(path).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent, ec);
    if (!stbi_write_png(path.c_str(), width, height, 3, rgb.data(), width * 3)) {
        *error = path + ": cannot write the screenshot";
        return false;
    }
    return true;
}

}  // namespace ug::editor
