// One interface for the three ways warplab gets an OpenGL 4.1+ core context: an SDL window
// (studies), headless OSMesa (Mesa llvmpipe; tests and CI), headless EGL (surfaceless or
// device platform; real GPUs, and Mesa releases without OSMesa). Everything else in the
// renderer runs the same on all three because it draws into its own framebuffers.
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
    // Window only: drawable size, title, vsync, visibility (hidden windows are for tests).
    int width = 1280;
    int height = 720;
    std::string title = "warplab";
    bool vsync = true;
    bool visible = true;
    bool fullscreen = false;  // borderless at the display's own mode (no mode switch)
    int display = 0;          // which display the window opens on (SDL's index)
};

// What the participant did since the last poll of a window (keys as characters: '\r' Enter,
// 27 Esc, '0'..'9', lower-case letters; others are dropped).
struct WindowInput {
    bool closed = false;
    double mouseDx = 0.0, mouseDy = 0.0;  // raw relative counts, no OS acceleration
    bool leftHeld = false;                // the left button is down now
    std::string keysPressed;              // in the order they were pressed
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
    virtual bool hasWindow() const { return false; }
    // Window only: show the default framebuffer (waits for vsync when enabled).
    virtual void swapBuffers() {}
    // Window only: handles pending window events; false once the user closed the window.
    virtual bool pumpEvents() { return true; }
    // Window only: input since the last poll (pumpEvents and pollInput both drain the queue).
    virtual WindowInput pollInput() { return {}; }
    // Window only: queues input as if the participant had given it; the next poll reads it
    // (scripted sessions in tests: mouse motion, a left press, keys as in WindowInput).
    virtual void injectInput(const WindowInput&) {}
    // Window only: relative mouse mode (hidden, unbounded, raw deltas) for studies.
    virtual void setRelativeMouse(bool) {}
    // The refresh rate of the display the window is on, Hz; 0 when unknown (Xvfb, headless).
    virtual double refreshHz() const { return 0.0; }
    // Whether swaps wait for vsync (the driver may refuse the swap interval).
    virtual bool vsyncOn() const { return false; }
    // Drawable size of the window's default framebuffer (0 x 0 when headless).
    virtual int drawableWidth() const { return 0; }
    virtual int drawableHeight() const { return 0; }

protected:
    GlContext() = default;
    // Loads the GL entry points through `loader`, reads the version strings and refuses
    // anything below 4.1 core. Every backend calls it once its context is current.
    void initialise(void* (*loader)(const char*), const char* backend);

private:
    GlInfo info_;
};

// Creates and makes current a context of the requested kind, or throws ContextError.
std::unique_ptr<GlContext> createContext(const ContextOptions& options);

}  // namespace warplab::renderer
