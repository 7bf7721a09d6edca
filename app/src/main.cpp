#include <csignal>

#include "app/app.h"

int main(int argc, char** argv) {
    // A session must outlive its output: when whoever reads stdout or stderr goes away (`| head`,
    // a dying `tee`, a closed terminal), a write fails with EPIPE instead of killing the process,
    // the stream stops printing, and the session runs on to its end.
    std::signal(SIGPIPE, SIG_IGN);
    return warplab::app::run(std::vector<std::string>(argv + 1, argv + argc));
}
