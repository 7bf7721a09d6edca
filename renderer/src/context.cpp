#include "renderer/context.h"

#include <cstdio>

#include "context_backends.h"
#include "gl/api.h"
#include "renderer/window.h"

namespace warplab::renderer {

GlBackend parseBackend(const std::string& name) {
    if (name == "osmesa") return GlBackend::OSMesa;
    if (name == "egl") return GlBackend::Egl;
    if (name == "window") return GlBackend::Window;
    throw ContextError("unknown GL backend '" + name + "' (expected osmesa, egl or window)");
}

const char* backendName(GlBackend backend) {
    switch (backend) {
        case GlBackend::OSMesa: return "osmesa";
        case GlBackend::Egl: return "egl";
        case GlBackend::Window: return "window";
    }
    return "?";
}

void GlContext::initialise(void* (*loader)(const char*), const char* backend) {
    const auto missing = gl::loadFunctions(loader);
    // glGetString is needed to say what we got; without it nothing else can be trusted.
    if (glGetString == nullptr || glGetIntegerv == nullptr)
        throw ContextError(std::string(backend) + " context offers no glGetString; it is not a usable OpenGL context");
    auto str = [](GLenum name) {
        const GLubyte* s = glGetString(name);
        return s ? std::string(reinterpret_cast<const char*>(s)) : std::string();
    };
    info_.vendor = str(GL_VENDOR);
    info_.renderer = str(GL_RENDERER);
    info_.version = str(GL_VERSION);
    info_.glslVersion = str(GL_SHADING_LANGUAGE_VERSION);
    info_.backend = backend;
    glGetIntegerv(GL_MAJOR_VERSION, &info_.major);
    glGetIntegerv(GL_MINOR_VERSION, &info_.minor);
    GLint mask = 0;
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &mask);
    info_.coreProfile = (mask & GL_CONTEXT_CORE_PROFILE_BIT) != 0;
    while (glGetError() != GL_NO_ERROR) {}
    if (info_.major < 4 || (info_.major == 4 && info_.minor < 1) || !info_.coreProfile) {
        throw ContextError("OpenGL 4.1 core profile is required but the " + std::string(backend) + " context is " +
                           info_.version + " (" + info_.renderer + ")" +
                           (info_.coreProfile ? "" : ", not a core profile"));
    }
    if (!missing.empty()) {
        throw ContextError("the " + std::string(backend) + " context (" + info_.version +
                           ") lacks the OpenGL function " + missing.front());
    }
}

std::unique_ptr<GlContext> createContext(const ContextOptions& options) {
    switch (options.backend) {
        case GlBackend::OSMesa: return createOsmesaContext(options);
        case GlBackend::Egl: return createEglContext(options);
        case GlBackend::Window: return createWindow(options);
    }
    throw ContextError("unknown GL backend");
}

}  // namespace warplab::renderer
