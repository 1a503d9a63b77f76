#include "editor/gl/offscreen_context.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <dlfcn.h>

namespace ug::editor::gl {

namespace {

constexpr const char* kInstallHint = "install Mesa's EGL and drivers (Debian: apt-get install libegl1 libgl1-mesa-dri)";

std::string eglErrorText(const char* what) {
    char text[96];
    std::snprintf(text, sizeof(text), "%s failed (EGL error 0x%04x)", what, unsigned(eglGetError()));
    return text;
}

bool hasExtension(const char* list, const char* name) {
    if (!list) return false;
    const size_t n = std::strlen(name);
    for (const char* p = std::strstr(list, name); p; p = std::strstr(p + n, name))
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

// A config that renders OpenGL into a pbuffer (what both paths need when they need a config at all).
EGLConfig chooseConfig(EGLDisplay display) {
    const EGLint attributes[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                 EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!eglChooseConfig(display, attributes, &config, 1, &count) || count < 1) return nullptr;
    return config;
}

}  // namespace

OffscreenContext::~OffscreenContext() { close(); }

void OffscreenContext::close() {
    if (!display_) return;
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context_) eglDestroyContext(display_, context_);
    if (surface_) eglDestroySurface(display_, surface_);
    eglTerminate(display_);
    display_ = context_ = surface_ = nullptr;
}

bool OffscreenContext::makeContext(void* display_ptr, void* config, std::string* error) {
    EGLDisplay display = display_ptr;
    if (!eglBindAPI(EGL_OPENGL_API)) {
        *error = eglErrorText("eglBindAPI(EGL_OPENGL_API)");
        return false;
    }
    // 4.5 where the driver has it (llvmpipe does), else 4.3: the renderer's shaders need 4.3.
    for (const EGLint minor : {5, 3}) {
        const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, minor,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
        context_ = eglCreateContext(display, config, EGL_NO_CONTEXT, attributes);
        if (context_) break;
    }
    if (!context_) {
        *error = eglErrorText("eglCreateContext (OpenGL 4.3 core)");
        return false;
    }
    if (!eglMakeCurrent(display, surface_ ? surface_ : EGL_NO_SURFACE, surface_ ? surface_ : EGL_NO_SURFACE,
                        context_)) {
        *error = eglErrorText("eglMakeCurrent");
        return false;
    }
    if (epoxy_gl_version() < 43) {
        *error = "OpenGL 4.3 or newer is needed, the EGL context gives " + std::to_string(epoxy_gl_version() / 10) +
                 "." + std::to_string(epoxy_gl_version() % 10);
        return false;
    }
    return true;
}

OffscreenStatus OffscreenContext::open(std::string* error) {
    close();
    // libepoxy dlopens libEGL on the first EGL call and aborts the process when it is not there.
    if (!dlopen("libEGL.so.1", RTLD_LAZY | RTLD_LOCAL)) {
        *error = "no EGL: cannot load libEGL.so.1 (" + std::string(dlerror()) + "); " + kInstallHint;
        return OffscreenStatus::NoContext;
    }
    std::string surfaceless_error;
    // Client extensions (EGL 1.5 or EGL_EXT_client_extensions): null when there are none.
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    const char* forced = std::getenv("UG_EGL");
    if (forced && std::strcmp(forced, "pbuffer") == 0) {
        surfaceless_error = "skipped (UG_EGL=pbuffer)";
    } else if (hasExtension(client, "EGL_MESA_platform_surfaceless") && hasExtension(client, "EGL_EXT_platform_base")) {
        EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr)) {
            display_ = display;
            const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
            const bool configless = hasExtension(extensions, "EGL_KHR_no_config_context") ||
                                    hasExtension(extensions, "EGL_MESA_configless_context");
            EGLConfig config = configless ? EGL_NO_CONFIG_KHR : chooseConfig(display);
            if (!hasExtension(extensions, "EGL_KHR_surfaceless_context")) {
                surfaceless_error = "the surfaceless display cannot make a context current without a surface";
            } else if (!configless && !config) {
                surfaceless_error = "the surfaceless display has no OpenGL config";
            } else if (makeContext(display, config, &surfaceless_error)) {
                platform_ = "EGL surfaceless";
            }
            if (platform_.empty()) close();
        } else {
            surfaceless_error = eglErrorText("eglInitialize (surfaceless)");
        }
    } else {
        surfaceless_error = "EGL_MESA_platform_surfaceless is not available";
    }
    if (platform_.empty()) {
        // The default display (X11 or a device, whatever the EGL vendor picks) with a pbuffer surface.
        std::string pbuffer_error;
        EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
        if (display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr)) {
            display_ = display;
            EGLConfig config = chooseConfig(display);
            const EGLint size[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
            if (!config) {
                pbuffer_error = "no OpenGL pbuffer config";
            } else if (!(surface_ = eglCreatePbufferSurface(display, config, size))) {
                pbuffer_error = eglErrorText("eglCreatePbufferSurface");
            } else if (makeContext(display, config, &pbuffer_error)) {
                platform_ = "EGL pbuffer";
            }
            if (platform_.empty()) close();
        } else {
            pbuffer_error = eglErrorText("eglInitialize (default display)");
        }
        if (platform_.empty()) {
            *error = "no OpenGL 4.3 core context without a display: surfaceless: " + surfaceless_error +
                     "; pbuffer: " + pbuffer_error + "; " + kInstallHint;
            return OffscreenStatus::NoContext;
        }
    }
    gl_version_ = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    renderer_ = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    GLint renderbuffer = 0, viewport[2] = {0, 0};
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &renderbuffer);
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
    max_size_ = std::min({renderbuffer, viewport[0], viewport[1]});
    return OffscreenStatus::Ok;
}

void OffscreenContext::finish() { glFinish(); }

OffscreenTarget::~OffscreenTarget() {
    if (fbo_) glDeleteFramebuffers(1, &fbo_);
    if (color_) glDeleteRenderbuffers(1, &color_);
    if (depth_) glDeleteRenderbuffers(1, &depth_);
}

bool OffscreenTarget::create(int width, int height, std::string* error) {
    width_ = width;
    height_ = height;
    glGenRenderbuffers(1, &color_);
    glBindRenderbuffer(GL_RENDERBUFFER, color_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    glGenRenderbuffers(1, &depth_);
    glBindRenderbuffer(GL_RENDERBUFFER, depth_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    glGenFramebuffers(1, &fbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    const GLenum gl_error = glGetError();  // e.g. GL_OUT_OF_MEMORY from the storage
    if (status != GL_FRAMEBUFFER_COMPLETE || gl_error != GL_NO_ERROR) {
        char text[160];
        std::snprintf(text, sizeof(text),
                      "cannot make a %d x %d framebuffer (status 0x%04x, GL error 0x%04x)", width, height,
                      unsigned(status), unsigned(gl_error));
        *error = text;
        return false;
    }
    return true;
}

void OffscreenTarget::bind() const {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    const GLenum attachment = GL_COLOR_ATTACHMENT0;
    glDrawBuffers(1, &attachment);
}

void OffscreenTarget::readPixels(std::vector<uint8_t>* rgba) const {
    const size_t row = size_t(width_) * 4;
    std::vector<uint8_t> bottom_up(row * size_t(height_));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
    rgba->resize(bottom_up.size());
    for (int y = 0; y < height_; ++y)
        std::memcpy(rgba->data() + size_t(y) * row, bottom_up.data() + size_t(height_ - 1 - y) * row, row);
}

}  // namespace ug::editor::gl
