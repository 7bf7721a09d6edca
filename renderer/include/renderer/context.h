// One interface for the three ways warplab gets an OpenGL 4.1+ core context: an SDL window
// (studies), headless OSMesa (Mesa llvmpipe; tests and CI), headless EGL (surfaceless or
// device platform; real GPUs, and Mesa releases without OSMesa). Everything else in the
// renderer runs the same on all three because it draws into its own framebuffers. What only
// a window has -- presenting, vsync, the participant's input -- is renderer/window.h's.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

namespace warplab::renderer {

enum class GlBackend { OSMesa, Egl, Window };

// "osmesa", "egl", "window"; throws ContextError naming the bad value.
GlBackend parseBackend(const std::string& name);
const char* backendName(GlBackend backend);

struct ContextOptions {
    GlBackend backend = GlBackend::OSMesa;
    // Window only (createWindow): drawable size, title, vsync, visibility (hidden windows are
    // for tests).
    int width = 1280;
    int height = 720;
    std::string title = "warplab";
    bool vsync = true;
    bool visible = true;
    bool fullscreen = false;  // borderless at the display's own mode (no mode switch)
    int display = 0;  // which display the window opens on (SDL's index)
};

struct GlInfo {
    std::string vendor;
    std::string renderer;
    std::string version;
    std::string glslVersion;
    std::string backend;  // which of our three paths made it
    int major = 0;
    int minor = 0;
    bool coreProfile = false;
};

// The context could not be made, or is older than 4.1 core. The message is one sentence
// fit to show the user.
class ContextError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class GlContext {
public:
    virtual ~GlContext() = default;
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    const GlInfo& info() const { return info_; }

protected:
    GlContext() = default;
    // Loads the GL entry points through `loader`, reads the version strings and refuses
    // anything below 4.1 core. Every backend calls it once its context is current.
    void initialise(void* (*loader)(const char*), const char* backend);

private:
    GlInfo info_;
};

// Creates and makes current a context of the requested kind, or throws ContextError. For
// GlBackend::Window this is createWindow's context (renderer/window.h) without its window.
std::unique_ptr<GlContext> createContext(const ContextOptions& options);

}  // namespace warplab::renderer
