// The editor window's title: the document's file name, a mark while it has unsaved changes, the app.
//   windowTitle("/scenes/meadow.json", false) == "meadow.json — Undergrowth"
//   windowTitle("/scenes/meadow.json", true)  == "meadow.json • — Undergrowth"
//   windowTitle("", true)                     == "untitled • — Undergrowth"   (File > New)
#pragma once

#include <string>

namespace ug::editor {

constexpr const char* kAppTitle = "Undergrowth";
constexpr const char* kUnsavedMark = "\xE2\x80\xA2";  // U+2022 BULLET

// `path` "" with `has_document` false: no document (loading the first one, or it failed): the app alone.
std::string windowTitle(const std::string& path, bool dirty, bool has_document = true);

}  // namespace ug::editor
