// Private: the study window's X errors as one sentence each. SDL 2.26's X11 backend leaves
// them to Xlib's defaults: its own handler (X11_SafetyNetErrHandler) only puts back a changed
// video mode and then calls Xlib's, which prints the raw request ("X Error of failed request:
// BadDrawable ...") and exits; a lost connection gets Xlib's "XIO: fatal IO error" and an
// exit. A window another program destroys ends instead through the window's own calls (the
// next swap or poll throws WindowLost, so a session ends as its code says), and a display
// that goes away ends the process with a sentence naming it.
#pragma once

#include <string>

struct SDL_Window;

namespace warplab::renderer::x11 {

// Installs warplab's handlers for `window` (an SDL window on X11) and forgets an earlier
// window's error. Call once the window and its context exist, every time: SDL puts its own
// handler back when it starts its video.
void watchWindowErrors(SDL_Window* window);

// Waits until the X server has answered everything sent so far, so that the errors met by the
// window's own teardown (SDL_DestroyWindow on a window already destroyed) reach warplab's
// handler. Call after destroying the window and before SDL_QuitSubSystem: SDL 2.26 puts Xlib's
// default handler back as it closes the display, and that handler exits with the raw text.
void settle();

// The first X error since watchWindowErrors(), as one sentence; "" when none. The later
// errors follow from the first (every call on a destroyed window fails), so they are dropped.
std::string windowError();

}  // namespace warplab::renderer::x11
