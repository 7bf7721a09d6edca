#include "plot.h"

#include <filesystem>

#include <sys/wait.h>
#include <unistd.h>

namespace warplab::bench {

// The plot is matplotlib's job; Debian's interpreter has it (python3 earlier on PATH may not).
// Run without a shell, so no path needs quoting; its output (stdout and stderr) is the reason
// when it fails.
std::string writePlot(const renderer::DataPaths& paths, const std::string& csv, const std::string& png,
                      const std::string& title, const std::string& budgetPng, double samplesPerShare) {
    const std::string script = paths.analysisDir + "/plot_bench.py";
    const char* python = "/usr/bin/python3";
    if (!std::filesystem::exists(script)) return "not written: " + script + " is missing";
    if (!std::filesystem::exists(python)) return "not written: /usr/bin/python3 is missing (scripts/install-deps.sh)";
    int out[2];
    if (pipe(out) != 0) return "not written: cannot run " + std::string(python);
    const pid_t pid = fork();
    if (pid < 0) {
        close(out[0]);
        close(out[1]);
        return "not written: cannot run " + std::string(python);
    }
    if (pid == 0) {
        dup2(out[1], STDOUT_FILENO);
        dup2(out[1], STDERR_FILENO);
        close(out[0]);
        close(out[1]);
        const std::string samples = std::to_string(samplesPerShare);
        const char* argv[] = {python,        script.c_str(), csv.c_str(),       png.c_str(),           "--title",
                              title.c_str(), "--budget-png", budgetPng.c_str(), "--samples-per-share", samples.c_str(),
                              nullptr};
        execv(python, const_cast<char* const*>(argv));
        _exit(127);
    }
    close(out[1]);
    std::string output;
    char buffer[512];
    for (ssize_t n; (n = read(out[0], buffer, sizeof buffer)) > 0;) output.append(buffer, static_cast<std::size_t>(n));
    close(out[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return "";
    while (!output.empty() && output.back() == '\n') output.pop_back();
    return "not written: " + (output.empty() ? "cannot run " + std::string(python) : output);
}

}  // namespace warplab::bench
