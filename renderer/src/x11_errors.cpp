#include "x11_errors.h"

#include <SDL_syswm.h>
#include <X11/Xlib.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>

namespace warplab::renderer::x11 {
namespace {

// Written by the handler, which Xlib calls from inside the X call that met the error, on the
// window's thread; read after that call returns. Fixed storage: a handler should not allocate.
char firstError[512];
bool failed = false;
Display* watched = nullptr;  // the watched window's display

int onError(Display* display, XErrorEvent* event) {
    if (failed) return 0;
    failed = true;
    char text[160] = "";
    XGetErrorText(display, event->error_code, text, sizeof text);
    // "BadDrawable (invalid Pixmap or Window parameter)": its name is what a person can look up.
    text[std::strcspn(text, " ")] = '\0';
    if (event->error_code == BadDrawable || event->error_code == BadWindow)
        std::snprintf(firstError, sizeof firstError,
                      "the window was destroyed by another program (the X server answered %s to a request on it)",
                      text);
    else
        std::snprintf(firstError, sizeof firstError,
                      "the X server refused a request of the window (%s, request code %d)", text,
                      static_cast<int>(event->request_code));
    return 0;  // go on: the window's next swap or poll reports it
}

// Xlib exits once this returns, and its callers cannot be unwound: say what happened and end.
// What a session committed before it is in its file, as after a kill.
[[noreturn]] int onIoError(Display* display) {
    const char* name = display != nullptr ? DisplayString(display) : "";
    std::fprintf(stderr,
                 "warplab: the connection to the X display '%s' was lost (the X server ended, or another "
                 "program killed the window); a session keeps every trial committed before it\n",
                 name != nullptr ? name : "");
    std::fflush(stdout);
    std::fflush(stderr);
    ::_exit(1);
}

}  // namespace

void watchWindowErrors(SDL_Window* window) {
    failed = false;
    firstError[0] = '\0';
    SDL_SysWMinfo info;
    SDL_VERSION(&info.version);
    watched = SDL_GetWindowWMInfo(window, &info) == SDL_TRUE && info.subsystem == SDL_SYSWM_X11 ? info.info.x11.display
                                                                                                : nullptr;
    XSetErrorHandler(&onError);
    XSetIOErrorHandler(&onIoError);
}

void settle() {
    if (watched != nullptr) XSync(watched, False);
    watched = nullptr;
}

std::string windowError() { return failed ? std::string(firstError) : std::string(); }

}  // namespace warplab::renderer::x11
