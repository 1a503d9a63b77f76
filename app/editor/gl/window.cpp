#include "editor/gl/window.h"

#include <epoxy/gl.h>
// epoxy must come first: GLFW would otherwise pull in the system GL header.
#include <GLFW/glfw3.h>

#include <cfloat>
#include <cstdlib>

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

namespace ug::editor::gl {

namespace {

// GLFW reports errors through a callback; the last one explains a failed glfwInit or window creation.
std::string g_last_glfw_error;
void onGlfwError(int code, const char* description) {
    g_last_glfw_error = std::string(description ? description : "unknown") + " (GLFW error " + std::to_string(code) + ")";
}

}  // namespace

Window::~Window() {
    if (imgui_ready_) {
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
    if (window_) glfwDestroyWindow(window_);
    // GLFW itself stays initialised until the process exits (see open()).
}

OpenStatus Window::open(const WindowOptions& options, std::string* error) {
    glfwSetErrorCallback(onGlfwError);
    g_last_glfw_error.clear();
    // Once per process, terminated at exit: closing the X connection between two windows of one process
    // (the bench opens several) lets Xvfb reset when its last client leaves, and under xvfb-run the next
    // connection is then refused.
    static bool glfw_initialised = false;
    if (!glfw_initialised && glfwInit()) {
        glfw_initialised = true;
        std::atexit(glfwTerminate);
    }
    if (!glfw_initialised) {
        *error = "cannot open a display: " + (g_last_glfw_error.empty() ? std::string("glfwInit failed") : g_last_glfw_error) +
                 " (set DISPLAY, or run under xvfb-run)";
        return OpenStatus::NoDisplay;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_DEPTH_BITS, 24);
    glfwWindowHint(GLFW_SAMPLES, 0);  // no MSAA: llvmpipe pays for every sample
    window_ = glfwCreateWindow(options.width, options.height, options.title, nullptr, nullptr);
    if (!window_) {
        *error = "cannot create an OpenGL 4.3 core window: " + g_last_glfw_error;
        return OpenStatus::Failed;
    }
    title_ = options.title;
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(options.vsync ? 1 : 0);
    if (epoxy_gl_version() < 43) {
        *error = "OpenGL 4.3 or newer is needed, the context gives " + std::to_string(epoxy_gl_version() / 10) + "." +
                 std::to_string(epoxy_gl_version() % 10);
        return OpenStatus::Failed;
    }
    gl_version_ = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    renderer_ = reinterpret_cast<const char*>(glGetString(GL_RENDERER));

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // scripted runs must not depend on (or leave) an imgui.ini
    ImGui::StyleColorsDark();
    if (!ImGui_ImplGlfw_InitForOpenGL(window_, true) || !ImGui_ImplOpenGL3_Init("#version 430")) {
        *error = "Dear ImGui's GLFW / OpenGL3 backends failed to start";
        return OpenStatus::Failed;
    }
    imgui_ready_ = true;
    return OpenStatus::Ok;
}

bool Window::shouldClose() const { return glfwWindowShouldClose(window_); }
void Window::requestClose() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }
void Window::cancelClose() { glfwSetWindowShouldClose(window_, GLFW_FALSE); }
void Window::pollEvents() { glfwPollEvents(); }

void Window::beginUiFrame(bool ignore_mouse) {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    if (ignore_mouse) ImGui::GetIO().MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
    ImGui::NewFrame();
}

void Window::renderUi() {
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void Window::swapBuffers() { glfwSwapBuffers(window_); }
void Window::finish() { glFinish(); }
void Window::setTitle(const std::string& title) {
    if (title == title_) return;
    title_ = title;
    glfwSetWindowTitle(window_, title_.c_str());
}

void Window::framebufferSize(int* width, int* height) const { glfwGetFramebufferSize(window_, width, height); }

}  // namespace ug::editor::gl
