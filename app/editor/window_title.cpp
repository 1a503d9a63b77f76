#include "editor/window_title.h"

#include <filesystem>

namespace ug::editor {

std::string windowTitle(const std::string& path, bool dirty, bool has_document) {
    if (!has_document) return kAppTitle;
    const std::string name = path.empty() ? "untitled" : std::filesystem::path(path).filename().string();
    return name + (dirty ? std::string(" ") + kUnsavedMark : std::string()) + " \xE2\x80\x94 " + kAppTitle;
}

}  // namespace ug::editor
