// Headless Mesa through OSMesa. libOSMesa is opened at run time rather than linked, so the
// binary still starts on systems whose Mesa dropped OSMesa (they use --gl egl).
#include <dlfcn.h>

#include <vector>

#include <GL/osmesa.h>

#include "context_backends.h"

namespace warplab::renderer {
namespace {

using CreateAttribsFn = OSMesaContext (*)(const int*, OSMesaContext);
using MakeCurrentFn = GLboolean (*)(OSMesaContext, void*, GLenum, GLsizei, GLsizei);
using DestroyFn = void (*)(OSMesaContext);
using GetProcFn = OSMESAproc (*)(const char*);

GetProcFn g_getProc = nullptr;

void* loadProc(const char* name) { return reinterpret_cast<void*>(g_getProc(name)); }

class OsmesaContext final : public GlContext {
public:
    OsmesaContext() {
        for (const char* name : {"libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so"}) {
            library_ = dlopen(name, RTLD_NOW | RTLD_LOCAL);
            if (library_ != nullptr) break;
        }
        if (library_ == nullptr)
            throw ContextError(
                "OSMesa is not installed (libOSMesa.so.8 not found); install libosmesa6 or use --gl egl");
        auto create = reinterpret_cast<CreateAttribsFn>(dlsym(library_, "OSMesaCreateContextAttribs"));
        makeCurrent_ = reinterpret_cast<MakeCurrentFn>(dlsym(library_, "OSMesaMakeCurrent"));
        destroy_ = reinterpret_cast<DestroyFn>(dlsym(library_, "OSMesaDestroyContext"));
        g_getProc = reinterpret_cast<GetProcFn>(dlsym(library_, "OSMesaGetProcAddress"));
        if (!create || !makeCurrent_ || !destroy_ || !g_getProc)
            throw ContextError(
                "the OSMesa library is too old to create core-profile contexts (no OSMesaCreateContextAttribs)");

        const int attribs[] = {OSMESA_FORMAT,
                               OSMESA_RGBA,
                               OSMESA_DEPTH_BITS,
                               0,  // we render into our own framebuffers
                               OSMESA_PROFILE,
                               OSMESA_CORE_PROFILE,
                               OSMESA_CONTEXT_MAJOR_VERSION,
                               4,
                               OSMESA_CONTEXT_MINOR_VERSION,
                               1,
                               0};
        context_ = create(attribs, nullptr);
        if (context_ == nullptr) throw ContextError("OSMesa could not create an OpenGL 4.1 core context");
        // OSMesa insists on a default colour buffer (bottom-up rows); nothing is drawn into
        // it, so a tiny one will do.
        buffer_.assign(4 * kBufferSize * kBufferSize, 0);
        if (!makeCurrent_(context_, buffer_.data(), GL_UNSIGNED_BYTE, kBufferSize, kBufferSize))
            throw ContextError("OSMesa could not make its context current");
        initialise(&loadProc, "osmesa");
    }

    ~OsmesaContext() override {
        if (context_ != nullptr) destroy_(context_);
        // libOSMesa stays loaded: Mesa keeps thread-local state that outlives dlclose badly.
    }

private:
    static constexpr int kBufferSize = 4;
    void* library_ = nullptr;
    MakeCurrentFn makeCurrent_ = nullptr;
    DestroyFn destroy_ = nullptr;
    OSMesaContext context_ = nullptr;
    std::vector<unsigned char> buffer_;
};

}  // namespace

std::unique_ptr<GlContext> createOsmesaContext(const ContextOptions&) { return std::make_unique<OsmesaContext>(); }

}  // namespace warplab::renderer
