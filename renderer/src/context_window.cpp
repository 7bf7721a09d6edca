// The study window: SDL2 with a GL 4.1 core context and vsync.
#include <SDL.h>

#include <cstdlib>
#include <cstring>

#include "context_backends.h"
#include "renderer/window.h"
#include "x11_errors.h"

namespace warplab::renderer {
namespace {

void* loadProc(const char* name) { return SDL_GL_GetProcAddress(name); }

const char* environment(const char* name) {
    const char* value = std::getenv(name);
    return value != nullptr ? value : "";
}

// Why no window can be shown, in one sentence, where SDL found no display: with DISPLAY unset
// or unreachable SDL 2.26 falls back to its offscreen driver (or, asked to, its dummy one),
// whose windows nobody sees -- a session would wait at a start screen no one can read.
std::string noDisplay(const std::string& driver) {
    const std::string asked = environment("SDL_VIDEODRIVER");
    if (!asked.empty())
        return "no window can be shown: SDL_VIDEODRIVER=" + asked + " draws into no screen" +
            (driver.empty() ? "" : " (SDL chose '" + driver + "')") + "; unset it and run on the machine's display";
    const std::string display = environment("DISPLAY"), wayland = environment("WAYLAND_DISPLAY");
    if (display.empty() && wayland.empty())
        return "no window can be shown: DISPLAY is not set (start warplab from the desktop, or set DISPLAY=:0 for "
               "the machine's own screen)";
    return "no window can be shown: the display '" + (display.empty() ? wayland : display) +
        "' cannot be reached (is its X server running, and may this user draw on it?)";
}

bool invisibleDriver(const char* driver) {
    return driver == nullptr || std::strcmp(driver, "offscreen") == 0 || std::strcmp(driver, "dummy") == 0;
}

class SdlWindow final : public WindowContext {
public:
    explicit SdlWindow(const ContextOptions& options) {
        // Nowhere to look for a display: said before SDL tries (and Wayland's client library
        // complains about XDG_RUNTIME_DIR). SDL_VIDEODRIVER may still name one (kmsdrm).
        if (!*environment("SDL_VIDEODRIVER") && !*environment("DISPLAY") && !*environment("WAYLAND_DISPLAY"))
            throw ContextError(noDisplay(""));
        if (SDL_InitSubSystem(SDL_INIT_VIDEO) != 0) throw ContextError(noDisplay(""));
        if (const char* driver = SDL_GetCurrentVideoDriver(); invisibleDriver(driver)) {
            const std::string why = noDisplay(driver != nullptr ? driver : "");
            SDL_QuitSubSystem(SDL_INIT_VIDEO);
            throw ContextError(why);
        }
        videoInitialised_ = true;
        SDL_GL_SetAttribute(SDL_GL_CONTEXT_MAJOR_VERSION, 4);
        SDL_GL_SetAttribute(SDL_GL_CONTEXT_MINOR_VERSION, 1);
        SDL_GL_SetAttribute(SDL_GL_CONTEXT_PROFILE_MASK, SDL_GL_CONTEXT_PROFILE_CORE);
        SDL_GL_SetAttribute(SDL_GL_CONTEXT_FLAGS, SDL_GL_CONTEXT_FORWARD_COMPATIBLE_FLAG);
        SDL_GL_SetAttribute(SDL_GL_DOUBLEBUFFER, 1);
        SDL_GL_SetAttribute(SDL_GL_DEPTH_SIZE, 0);  // the renderer has its own depth buffers
        Uint32 flags = SDL_WINDOW_OPENGL | (options.visible ? SDL_WINDOW_SHOWN : SDL_WINDOW_HIDDEN);
        if (options.fullscreen) flags |= SDL_WINDOW_FULLSCREEN_DESKTOP;
        if (options.display < 0 || options.display >= SDL_GetNumVideoDisplays())
            throw ContextError("there is no display " + std::to_string(options.display) + " (this machine has " +
                               std::to_string(SDL_GetNumVideoDisplays()) + ")");
        window_ =
            SDL_CreateWindow(options.title.c_str(), SDL_WINDOWPOS_CENTERED_DISPLAY(options.display),
                             SDL_WINDOWPOS_CENTERED_DISPLAY(options.display), options.width, options.height, flags);
        if (window_ == nullptr) throw ContextError(std::string("cannot open a window: ") + SDL_GetError());
        context_ = SDL_GL_CreateContext(window_);
        if (context_ == nullptr)
            throw ContextError(std::string("the window system offers no OpenGL 4.1 core context: ") + SDL_GetError());
        // Adaptive vsync is not what a study wants (it tears); plain vsync or, if refused, none,
        // which the frame log will show as measured frame times.
        vsync_ = SDL_GL_SetSwapInterval(options.vsync ? 1 : 0) == 0 && options.vsync && SDL_GL_GetSwapInterval() == 1;
        initialise(&loadProc, "window");
        if (std::strcmp(SDL_GetCurrentVideoDriver(), "x11") == 0) x11::watchWindowErrors(window_);
        // Typed text, for answers typed on screen: the window system applies the keyboard
        // layout, Shift, dead keys and input methods, which key codes alone cannot give.
        SDL_StartTextInput();
    }

    ~SdlWindow() override {
        if (videoInitialised_) SDL_StopTextInput();
        if (context_ != nullptr) SDL_GL_DeleteContext(context_);
        if (window_ != nullptr) SDL_DestroyWindow(window_);
        x11::settle();
        if (videoInitialised_) SDL_QuitSubSystem(SDL_INIT_VIDEO);
    }

    void swapBuffers() override {
        SDL_GL_SwapWindow(window_);
        throwIfLost();
    }
    bool pumpEvents() override {
        const WindowInput in = pollInput();
        return !in.closed && !in.closeAsked;
    }
    WindowInput pollInput() override {
        WindowInput in;
        bool pressed = false;
        SDL_Event event;
        while (SDL_PollEvent(&event)) {
            switch (event.type) {
                // The window manager's close comes as the window's close and then, the last
                // window asked to close, a quit; a quit alone is a signal (Ctrl+C, SIGTERM).
                case SDL_QUIT: in.closed = true; break;
                case SDL_WINDOWEVENT:
                    switch (event.window.event) {
                        case SDL_WINDOWEVENT_CLOSE: in.closeAsked = true; break;
                        case SDL_WINDOWEVENT_FOCUS_LOST:
                        case SDL_WINDOWEVENT_MINIMIZED:
                        case SDL_WINDOWEVENT_HIDDEN: in.focusLost = true; break;
                        default: break;
                    }
                    break;
                case SDL_MOUSEBUTTONDOWN:
                    if (event.button.button == SDL_BUTTON_LEFT) pressed = true;
                    break;
                case SDL_MOUSEMOTION:
                    in.mouseDx += event.motion.xrel;
                    in.mouseDy += event.motion.yrel;
                    break;
                case SDL_TEXTINPUT: in.text += event.text.text; break;
                case SDL_KEYDOWN: {
                    const SDL_Keycode k = event.key.keysym.sym;
                    // Backspace is editing, not a character, so it has no text event of its
                    // own; held, it repeats as held letters do.
                    if (k == SDLK_BACKSPACE) in.text += kTypedBackspace;
                    if (event.key.repeat) break;
                    if (k == SDLK_RETURN || k == SDLK_KP_ENTER)
                        in.keysPressed += '\r';
                    else if (k == SDLK_ESCAPE)
                        in.keysPressed += static_cast<char>(27);
                    else if ((k >= SDLK_0 && k <= SDLK_9) || (k >= SDLK_a && k <= SDLK_z))
                        in.keysPressed += static_cast<char>(k);
                    else if (k >= SDLK_KP_1 && k <= SDLK_KP_9)
                        in.keysPressed += static_cast<char>('1' + (k - SDLK_KP_1));
                    // A presentation clicker's "next" and "previous" are PageDown and PageUp.
                    else if (k == SDLK_RIGHTBRACKET || k == SDLK_PAGEDOWN)
                        in.keysPressed += ']';
                    else if (k == SDLK_LEFTBRACKET || k == SDLK_PAGEUP)
                        in.keysPressed += '[';
                    break;
                }
                default: break;
            }
        }
        // Held now, or pressed since the last poll: a click shorter than a frame still shows as
        // one frame held, and the game scores presses.
        in.leftHeld = pressed || (SDL_GetMouseState(nullptr, nullptr) & SDL_BUTTON(SDL_BUTTON_LEFT)) != 0;
        if (in.closeAsked) in.closed = false;  // the quit that came with it
        throwIfLost();
        return in;
    }
    void injectInput(const WindowInput& in) override {
        SDL_Event e{};
        if (in.mouseDx != 0.0 || in.mouseDy != 0.0) {
            e = SDL_Event{};
            e.type = SDL_MOUSEMOTION;
            e.motion.xrel = static_cast<Sint32>(in.mouseDx);
            e.motion.yrel = static_cast<Sint32>(in.mouseDy);
            SDL_PushEvent(&e);
        }
        if (in.leftHeld) {
            e = SDL_Event{};
            e.type = SDL_MOUSEBUTTONDOWN;
            e.button.button = SDL_BUTTON_LEFT;
            e.button.state = SDL_PRESSED;
            SDL_PushEvent(&e);
        }
        for (const char c : in.keysPressed) {
            e = SDL_Event{};
            e.type = SDL_KEYDOWN;
            e.key.state = SDL_PRESSED;
            e.key.keysym.sym = c == '\r' ? SDLK_RETURN : static_cast<SDL_Keycode>(c);
            SDL_PushEvent(&e);
        }
        injectText(in.text);
    }
    // As the window system sends typing: text events of whole UTF-8 characters, each within
    // an event's fixed buffer, and a key press for each Backspace, in the order given.
    static void injectText(const std::string& text) {
        constexpr std::size_t kMaxBytes = sizeof(SDL_TextInputEvent::text) - 1;  // and its terminator
        std::string run;
        auto flush = [&run] {
            if (run.empty()) return;
            SDL_Event e{};
            e.type = SDL_TEXTINPUT;
            run.copy(e.text.text, run.size());
            SDL_PushEvent(&e);
            run.clear();
        };
        for (std::size_t at = 0; at < text.size();) {
            if (text[at] == kTypedBackspace) {
                flush();
                SDL_Event e{};
                e.type = SDL_KEYDOWN;
                e.key.state = SDL_PRESSED;
                e.key.keysym.sym = SDLK_BACKSPACE;
                SDL_PushEvent(&e);
                ++at;
                continue;
            }
            std::size_t next = at + 1;  // past this character's continuation bytes
            while (next < text.size() && (static_cast<unsigned char>(text[next]) & 0xC0) == 0x80) ++next;
            if (run.size() + (next - at) > kMaxBytes) flush();
            run.append(text, at, next - at);
            at = next;
        }
        flush();
    }
    void setRelativeMouse(bool on) override {
        // Raw deltas: relative mode without the OS pointer's acceleration (SDL's default warps
        // the pointer on some systems, which would add acceleration).
        SDL_SetHint(SDL_HINT_MOUSE_RELATIVE_MODE_WARP, "0");
        SDL_SetRelativeMouseMode(on ? SDL_TRUE : SDL_FALSE);
    }
    double refreshHz() const override {
        SDL_DisplayMode mode;
        const int display = SDL_GetWindowDisplayIndex(window_);
        if (display < 0 || SDL_GetCurrentDisplayMode(display, &mode) != 0) return 0.0;
        return mode.refresh_rate;
    }
    bool vsyncOn() const override { return vsync_; }
    int drawableWidth() const override {
        int w = 0, h = 0;
        SDL_GL_GetDrawableSize(window_, &w, &h);
        return w;
    }
    int drawableHeight() const override {
        int w = 0, h = 0;
        SDL_GL_GetDrawableSize(window_, &w, &h);
        return h;
    }

private:
    static void throwIfLost() {
        if (const std::string error = x11::windowError(); !error.empty()) throw WindowLost(error);
    }

    bool vsync_ = false;
    bool videoInitialised_ = false;
    SDL_Window* window_ = nullptr;
    SDL_GLContext context_ = nullptr;
};

}  // namespace

std::unique_ptr<WindowContext> createWindow(const ContextOptions& options) {
    return std::make_unique<SdlWindow>(options);
}

}  // namespace warplab::renderer
