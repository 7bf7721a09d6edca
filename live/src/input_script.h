// The --input-script of live sessions and free play (docs/live-sessions.md "Scripted input"):
// what the window receives at each moment, as if from the participant.
#pragma once

#include <map>
#include <string>

#include "renderer/window.h"

namespace warplab::live {

class InputScript {
public:
    InputScript() = default;  // an empty script: nothing is injected
    // Reads the script (strict/file.h: a regular file, bounded); throws strict::Error, a
    // std::runtime_error, naming the file, and the line of a bad action or number.
    explicit InputScript(const std::string& path);

    // Queues what the script holds for `when` (a frame number, "start" or "end") on the window.
    void inject(renderer::Window& window, const std::string& when) const;

private:
    std::map<std::string, renderer::WindowInput> at_;
};

}  // namespace warplab::live
