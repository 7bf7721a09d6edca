// Headless EGL: the device platform first (picks a real GPU where there is one), then Mesa's
// surfaceless platform (llvmpipe when there is no GPU), then the default display.
// WARPLAB_EGL_PLATFORM=device|surfaceless|default forces one.
#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "context_backends.h"

namespace warplab::renderer {
namespace {

bool hasExtension(const char* list, const char* name) {
    if (list == nullptr) return false;
    const std::size_t n = std::strlen(name);
    for (const char* p = std::strstr(list, name); p != nullptr; p = std::strstr(p + 1, name))
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

void* g_libOpenGL = nullptr;

// Core entry points: eglGetProcAddress returns them when EGL_KHR_get_all_proc_addresses is
// there (Mesa, NVIDIA); otherwise they come straight from glvnd's libOpenGL.
void* loadProc(const char* name) {
    if (void* p = reinterpret_cast<void*>(eglGetProcAddress(name))) return p;
    if (g_libOpenGL == nullptr) g_libOpenGL = dlopen("libOpenGL.so.0", RTLD_NOW | RTLD_GLOBAL);
    return g_libOpenGL ? dlsym(g_libOpenGL, name) : nullptr;
}

class EglContext final : public GlContext {
public:
    EglContext() {
        const char* forced = std::getenv("WARPLAB_EGL_PLATFORM");
        const std::string want = forced ? forced : "";
        if (!want.empty() && want != "device" && want != "surfaceless" && want != "default")
            throw ContextError("WARPLAB_EGL_PLATFORM='" + want + "' is not one of device, surfaceless, default");
        const char* clientExt = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
        auto getPlatformDisplay =
            reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));

        std::string tried;
        auto attempt = [&](EGLDisplay display, const char* label) {
            if (display == EGL_NO_DISPLAY) return false;
            if (tryDisplay(display)) {
                platform_ = label;
                return true;
            }
            tried += std::string(tried.empty() ? "" : ", ") + label + " (EGL error 0x" + hex(eglGetError()) + ")";
            return false;
        };

        bool ok = false;
        if (!ok && (want.empty() || want == "device") && getPlatformDisplay &&
            hasExtension(clientExt, "EGL_EXT_platform_device")) {
            ok = tryDevices(getPlatformDisplay, attempt);
        }
        if (!ok && (want.empty() || want == "surfaceless") && getPlatformDisplay &&
            hasExtension(clientExt, "EGL_MESA_platform_surfaceless")) {
            ok =
                attempt(getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr), "surfaceless");
        }
        if (!ok && (want.empty() || want == "default")) ok = attempt(eglGetDisplay(EGL_DEFAULT_DISPLAY), "default");
        if (!ok)
            throw ContextError("EGL could not create an OpenGL 4.1 core context (tried: " +
                               (tried.empty() ? std::string("no EGL platform available") : tried) + ")");
        initialise(&loadProc, ("egl-" + platform_).c_str());
    }

    ~EglContext() override {
        if (display_ != EGL_NO_DISPLAY) {
            eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            if (surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, surface_);
            if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
            eglTerminate(display_);
        }
    }

private:
    static std::string hex(EGLint v) {
        char buf[16];
        std::snprintf(buf, sizeof buf, "%04X", static_cast<unsigned>(v));
        return buf;
    }

    template <typename Attempt>
    bool tryDevices(PFNEGLGETPLATFORMDISPLAYEXTPROC getPlatformDisplay, Attempt& attempt) {
        auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
        auto queryDeviceString =
            reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
        if (!queryDevices) return false;
        EGLint count = 0;
        if (!queryDevices(0, nullptr, &count) || count <= 0) return false;
        std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
        queryDevices(count, devices.data(), &count);
        // Hardware devices only: Mesa's software device is what surfaceless gives anyway.
        for (EGLint i = 0; i < count; ++i) {
            const char* ext = queryDeviceString ? queryDeviceString(devices[i], EGL_EXTENSIONS) : nullptr;
            if (hasExtension(ext, "EGL_MESA_device_software")) continue;
            if (attempt(getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr), "device")) return true;
        }
        return false;
    }

    bool tryDisplay(EGLDisplay display) {
        EGLint major = 0, minor = 0;
        if (!eglInitialize(display, &major, &minor)) return false;
        if (!eglBindAPI(EGL_OPENGL_API)) {
            eglTerminate(display);
            return false;
        }
        const char* ext = eglQueryString(display, EGL_EXTENSIONS);
        const EGLint contextAttribs[] = {
            EGL_CONTEXT_MAJOR_VERSION,           4,       EGL_CONTEXT_MINOR_VERSION, 1, EGL_CONTEXT_OPENGL_PROFILE_MASK,
            EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
        EGLConfig config = nullptr;
        const bool configless =
            hasExtension(ext, "EGL_KHR_no_config_context") || hasExtension(ext, "EGL_MESA_configless_context");
        const bool surfaceless = hasExtension(ext, "EGL_KHR_surfaceless_context");
        if (!configless || !surfaceless) {
            const EGLint configAttribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                            EGL_NONE};
            EGLint n = 0;
            if (!eglChooseConfig(display, configAttribs, &config, 1, &n) || n < 1) {
                eglTerminate(display);
                return false;
            }
        }
        EGLContext context =
            eglCreateContext(display, configless ? EGL_NO_CONFIG_KHR : config, EGL_NO_CONTEXT, contextAttribs);
        if (context == EGL_NO_CONTEXT) {
            eglTerminate(display);
            return false;
        }
        EGLSurface surface = EGL_NO_SURFACE;
        if (!surfaceless) {
            const EGLint pbufferAttribs[] = {EGL_WIDTH, 4, EGL_HEIGHT, 4, EGL_NONE};
            surface = eglCreatePbufferSurface(display, config, pbufferAttribs);
        }
        if (!eglMakeCurrent(display, surface, surface, context)) {
            if (surface != EGL_NO_SURFACE) eglDestroySurface(display, surface);
            eglDestroyContext(display, context);
            eglTerminate(display);
            return false;
        }
        display_ = display;
        context_ = context;
        surface_ = surface;
        return true;
    }

    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLContext context_ = EGL_NO_CONTEXT;
    EGLSurface surface_ = EGL_NO_SURFACE;
    std::string platform_;
};

}  // namespace

std::unique_ptr<GlContext> createEglContext(const ContextOptions&) { return std::make_unique<EglContext>(); }

}  // namespace warplab::renderer
