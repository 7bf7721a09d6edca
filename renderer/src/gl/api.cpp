#include "gl/api.h"

namespace warplab::gl {

namespace fn {
#define WARPLAB_GL(type, name) type name = nullptr;
#include "gl/functions.inc"
#undef WARPLAB_GL
}  // namespace fn

std::vector<std::string> loadFunctions(ProcAddressLoader loader) {
    std::vector<std::string> missing;
#define WARPLAB_GL(type, name)                        \
    fn::name = reinterpret_cast<type>(loader(#name)); \
    if (fn::name == nullptr) missing.emplace_back(#name);
#include "gl/functions.inc"
#undef WARPLAB_GL
    return missing;
}

}  // namespace warplab::gl
