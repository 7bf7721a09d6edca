// The study window: what a window has and a headless context has not -- presenting the
// default framebuffer, vsync, the display's refresh, the drawable size, and the participant's
// input (raw relative mouse counts, the left button, keys). Kept apart from GlContext so
// that participant input is not part of what every context is; the SDL backend
// (context_window.cpp) makes one object that is both.
#pragma once

#include <memory>
#include <string>

#include "renderer/context.h"

namespace warplab::renderer {

// Backspace in WindowInput::text: typed text never holds a control character, so one byte
// can stand for the key that takes a character back (the games read it as their own
// kTextBackspace, the same byte).
inline constexpr char kTypedBackspace = '\b';

// What the participant did since the last poll of a window (keys as characters: '\r' Enter,
// 27 Esc, '0'..'9', lower-case letters, '[' and ']' -- PageUp arrives as '[' and PageDown as
// ']', as a presentation clicker sends them; others are dropped).
struct WindowInput {
    // Told to end now: SDL's quit without a window's close (SIGINT or SIGTERM, Ctrl+C in the
    // terminal that started it).
    bool closed = false;
    // The window manager asked the window to close (its close button, alt+F4): the window
    // itself is still there, and whoever reads this may ask before anything ends.
    bool closeAsked = false;
    // The window left the participant: it lost the keyboard focus, was minimised or hidden.
    bool focusLost = false;
    double mouseDx = 0.0, mouseDy = 0.0;  // raw relative counts, no OS acceleration
    bool leftHeld = false;  // the left button is down now
    std::string keysPressed;  // in the order they were pressed
    // The text typed, as the window system composed it (UTF-8: layouts, Shift, dead keys and
    // input methods applied), in order, each Backspace as kTypedBackspace. A letter or digit
    // key arrives both here and in keysPressed; Enter and Esc only in keysPressed.
    std::string text;
};

// The window system took the window away while it was in use: another program destroyed it,
// or the X server refused a request on it. what() is one sentence saying which.
class WindowLost : public ContextError {
public:
    using ContextError::ContextError;
};

class Window {
public:
    virtual ~Window() = default;
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    // Shows the default framebuffer (waits for vsync when enabled). Throws WindowLost once the
    // window system has taken the window away (as pollInput does).
    virtual void swapBuffers() = 0;
    // Handles pending window events; false once the user closed the window (or asked to).
    virtual bool pumpEvents() = 0;
    // Input since the last poll (pumpEvents and pollInput both drain the queue).
    virtual WindowInput pollInput() = 0;
    // Queues input as if the participant had given it; the next poll reads it (scripted
    // sessions in tests: mouse motion, a left press, keys and text as in WindowInput; the
    // text arrives as text only, without the key presses that would have typed it).
    virtual void injectInput(const WindowInput& input) = 0;
    // Relative mouse mode (hidden, unbounded, raw deltas) for studies.
    virtual void setRelativeMouse(bool on) = 0;
    // The refresh rate of the display the window is on, Hz; 0 when unknown (Xvfb).
    virtual double refreshHz() const = 0;
    // Whether swaps wait for vsync (the driver may refuse the swap interval).
    virtual bool vsyncOn() const = 0;
    // Drawable size of the window's default framebuffer, pixels.
    virtual int drawableWidth() const = 0;
    virtual int drawableHeight() const = 0;

protected:
    Window() = default;
};

// A window and the GL context that draws into it, current from creation on.
class WindowContext : public GlContext, public Window {
protected:
    WindowContext() = default;
};

// Opens a window with the options' size, title, vsync, visibility, full screen and display
// (options.backend is not read), or throws ContextError: also where there is no display to
// show it on (DISPLAY unset or unreachable, SDL_VIDEODRIVER=offscreen or dummy), rather than
// drawing into one of SDL's invisible stand-ins.
std::unique_ptr<WindowContext> createWindow(const ContextOptions& options);

}  // namespace warplab::renderer
