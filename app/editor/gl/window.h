// The editor's window: GLFW with an OpenGL 4.3 core context (loaded through libepoxy) and Dear ImGui's
// GLFW and OpenGL3 backends. The only place a window or context is made; everything else sees sizes,
// strings and ImGui.
#pragma once

#include <string>

struct GLFWwindow;

namespace ug::editor::gl {

struct WindowOptions {
    int width = 1280;
    int height = 720;
    const char* title = "Undergrowth";
    bool vsync = true;  // off for scripted runs and benchmarks, which measure frame times
};

enum class OpenStatus { Ok, NoDisplay, Failed };

class Window {
public:
    Window() = default;
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    // NoDisplay: GLFW cannot reach a display (no DISPLAY, no X server); Failed: a display is there but no
    // OpenGL 4.3 core context could be made, or ImGui's backends failed. *error says which and why.
    OpenStatus open(const WindowOptions& options, std::string* error);

    bool shouldClose() const;
    void requestClose();
    void cancelClose();  // the user chose to keep editing (the unsaved-changes prompt)
    void pollEvents();
    // The backends' NewFrame, then ImGui::NewFrame. `ignore_mouse` (scripted runs): the pointer counts as
    // outside the window, so wherever the X server left it, no widget is hovered in a screenshot.
    void beginUiFrame(bool ignore_mouse = false);
    void renderUi();      // ImGui::Render and the OpenGL3 backend's draw
    void swapBuffers();
    void finish();        // glFinish: frame times that include the GPU's (llvmpipe's) work
    void framebufferSize(int* width, int* height) const;
    // Sets the title bar's text (UTF-8); a title equal to the current one costs nothing (called per frame).
    void setTitle(const std::string& title);
    const std::string& title() const { return title_; }
    const std::string& glVersion() const { return gl_version_; }
    const std::string& rendererName() const { return renderer_; }

private:
    GLFWwindow* window_ = nullptr;
    bool imgui_ready_ = false;
    std::string gl_version_;
    std::string renderer_;
    std::string title_;
};

}  // namespace ug::editor::gl
