// Rendering without a display (`undergrowth render`, the bench's render rows): an EGL OpenGL core context
// with no window, and a framebuffer object to draw into and read back. Mesa's EGL gives one without X or
// Wayland: EGL_MESA_platform_surfaceless first (no surface at all), else the default display with a 1 x 1
// pbuffer (some drivers want a surface to make a context current; we still draw into the FBO).
//
//   OffscreenContext context;
//   if (context.open(&error) != OffscreenStatus::Ok) ...;     // current on this thread from here on
//   OffscreenTarget target;
//   if (!target.create(1280, 720, &error)) ...;
//   target.bind();  renderer.render(camera, 1280, 720, lod);  target.readPixels(&rgba);
//
// UG_EGL=pbuffer skips the surfaceless platform (for a driver whose surfaceless path misbehaves; the
// tests use it to run the fallback). libEGL is loaded at run time by libepoxy, which aborts the process
// when it is missing; open() looks for it first so a machine without it gets a message instead.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace ug::editor::gl {

enum class OffscreenStatus { Ok, NoContext };

class OffscreenContext {
public:
    OffscreenContext() = default;
    ~OffscreenContext();
    OffscreenContext(const OffscreenContext&) = delete;
    OffscreenContext& operator=(const OffscreenContext&) = delete;

    // NoContext: no libEGL, no EGL display, or no OpenGL 4.3+ core context on it; *error says which
    // and what to install. On Ok the context is current on the calling thread.
    OffscreenStatus open(std::string* error);

    void finish();  // glFinish: the GPU's (llvmpipe's) work is done
    int maxSize() const { return max_size_; }  // the largest framebuffer side the context supports
    const std::string& glVersion() const { return gl_version_; }
    const std::string& rendererName() const { return renderer_; }
    const std::string& platform() const { return platform_; }  // "EGL surfaceless" or "EGL pbuffer"

private:
    bool makeContext(void* display, void* config, std::string* error);
    void close();

    void* display_ = nullptr;  // EGLDisplay
    void* context_ = nullptr;  // EGLContext
    void* surface_ = nullptr;  // EGLSurface: the pbuffer, or none (surfaceless)
    int max_size_ = 0;
    std::string gl_version_, renderer_, platform_;
};

// A framebuffer object of RGBA8 colour and 24-bit depth, the size of the picture.
class OffscreenTarget {
public:
    OffscreenTarget() = default;
    ~OffscreenTarget();
    OffscreenTarget(const OffscreenTarget&) = delete;
    OffscreenTarget& operator=(const OffscreenTarget&) = delete;

    // Contract: a context is current. Fails (with the reason) when the framebuffer is incomplete.
    bool create(int width, int height, std::string* error);
    void bind() const;  // GL_FRAMEBUFFER = this target, drawing into colour attachment 0
    // The colour attachment as RGBA8, rows top-down (GL's are bottom-up).
    void readPixels(std::vector<uint8_t>* rgba) const;
    int width() const { return width_; }
    int height() const { return height_; }

private:
    unsigned fbo_ = 0, color_ = 0, depth_ = 0;
    int width_ = 0, height_ = 0;
};

}  // namespace ug::editor::gl
