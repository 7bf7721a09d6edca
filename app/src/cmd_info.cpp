#include <iostream>

#include "commands.h"
#include "renderer/window.h"

namespace warplab::app {

int runInfo(const ParsedArgs& args) {
    renderer::ContextOptions options;
    options.backend = backendFrom(args, renderer::GlBackend::OSMesa);
    options.visible = false;
    options.width = 64;
    options.height = 64;
    const auto context = renderer::createContext(options);
    const auto& info = context->info();
    // A window's context is the window (renderer/window.h): what the display says of itself.
    const auto* window = dynamic_cast<const renderer::Window*>(context.get());
    std::cout << "backend:  " << info.backend << "\n"
              << "vendor:   " << info.vendor << "\n"
              << "renderer: " << info.renderer << "\n"
              << "version:  " << info.version << "\n"
              << "glsl:     " << info.glslVersion << "\n"
              << "profile:  " << (info.coreProfile ? "core" : "compatibility") << " " << info.major << "." << info.minor
              << "\n";
    if (window) {
        const double hz = window->refreshHz();
        std::cout << "refresh:  "
                  << (hz > 0.0 ? shown(hz) + " Hz, as the display reports it"
                               : std::string("unknown: the display reports none (0 Hz)"))
                  << "\n"
                  << "vsync:    " << (window->vsyncOn() ? "on" : "off: the driver refused a swap interval of 1")
                  << "\n";
    }
    return 0;
}

// The command's options, beside the code that reads them.
Command infoCommand() {
    return {{"info",
             "Print the vendor, renderer and version of the OpenGL context a backend gives; for a window,\n"
             "also the display's refresh as it reports it and whether vsync took.",
             "warplab info [--gl osmesa|egl|window]",
             {glOption("osmesa")}},
            &runInfo};
}

}  // namespace warplab::app
