#include <iostream>

#include "commands.h"

namespace warplab::app {

int runInfo(const ParsedArgs& args) {
    renderer::ContextOptions options;
    options.backend = backendFrom(args, renderer::GlBackend::OSMesa);
    options.visible = false;
    options.width = 64;
    options.height = 64;
    const auto context = renderer::createContext(options);
    const auto& info = context->info();
    std::cout << "backend:  " << info.backend << "\n"
              << "vendor:   " << info.vendor << "\n"
              << "renderer: " << info.renderer << "\n"
              << "version:  " << info.version << "\n"
              << "glsl:     " << info.glslVersion << "\n"
              << "profile:  " << (info.coreProfile ? "core" : "compatibility") << " " << info.major << "." << info.minor
              << "\n";
    return 0;
}

// The command's options, beside the code that reads them.
Command infoCommand() {
    return {{"info",
             "Print the vendor, renderer and version of the OpenGL context a backend gives.",
             "warplab info [--gl osmesa|egl|window]",
             {glOption("osmesa")}},
            &runInfo};
}

}  // namespace warplab::app
