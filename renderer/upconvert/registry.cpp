// The one list of upconversion methods. A new method registers here and is then available to
// the bench (--methods) and, through its name, to the study modes.
#include <functional>
#include <stdexcept>

#include "renderer/gbuffer_gl.h"
#include "renderer/upconvert.h"
#include "renderer/upconvert/simple_methods.h"

namespace warplab::renderer {
namespace {

struct Entry {
    const char* name;
    std::function<std::unique_ptr<UpconversionMethod>(const DataPaths&)> make;
};

const std::vector<Entry>& registry() {
    static const std::vector<Entry> entries = {
        {"hold15", [](const DataPaths& p) { return makeHold(p, 15.0); }},
        {"hold30", [](const DataPaths& p) { return makeHold(p, 30.0); }},
        {"hold60", [](const DataPaths& p) { return makeHold(p, 60.0); }},
        {"hold120", [](const DataPaths& p) { return makeHold(p, 120.0); }},
        {"blend", [](const DataPaths& p) { return makeBlend(p); }},
    };
    return entries;
}

}  // namespace

std::vector<std::string> methodNames() {
    std::vector<std::string> names;
    for (const auto& e : registry()) names.emplace_back(e.name);
    return names;
}

std::unique_ptr<UpconversionMethod> makeMethod(const std::string& name, const DataPaths& paths) {
    for (const auto& e : registry())
        if (name == e.name) return e.make(paths);
    std::string known;
    for (const auto& e : registry()) known += std::string(known.empty() ? "" : ", ") + e.name;
    throw std::invalid_argument("unknown method '" + name + "' (known: " + known + ")");
}

DisplayImages readBack(const DisplayFrame& frame) {
    const auto& g = frame.buffer().impl();
    return {readColourAttachment(g), readIdAttachment(g), readVectorAttachment(g, 4)};
}

}  // namespace warplab::renderer
