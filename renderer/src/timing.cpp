#include "renderer/timing.h"

#include <chrono>
#include <cmath>
#include <limits>

#include "gl/check.h"
#include "gl/objects.h"

namespace warplab::renderer {

struct PassTimer::Impl {
    gl::Query query;
    std::chrono::steady_clock::time_point start;
};

PassTimer::PassTimer() : impl_(std::make_unique<Impl>()) { impl_->query = gl::Query::create(); }
PassTimer::~PassTimer() = default;

void PassTimer::begin() {
    glFinish();
    glBeginQuery(GL_TIME_ELAPSED, impl_->query.id());
    impl_->start = std::chrono::steady_clock::now();
}

PassTime PassTimer::end() {
    glEndQuery(GL_TIME_ELAPSED);
    glFinish();
    PassTime time;
    time.wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - impl_->start).count();
    GLint available = 0;
    glGetQueryObjectiv(impl_->query.id(), GL_QUERY_RESULT_AVAILABLE, &available);
    if (available) {
        GLuint64 ns = 0;
        glGetQueryObjectui64v(impl_->query.id(), GL_QUERY_RESULT, &ns);
        time.gpuMs = static_cast<double>(ns) * 1e-6;
        // The GPU's interval lies inside the glFinish-bracketed wall interval; a longer one is
        // a driver returning nonsense (seen: Mesa llvmpipe through EGL surfaceless reports
        // absolute timestamps), so it is dropped rather than reported.
        if (time.gpuMs > 1.5 * time.wallMs + 1.0) time.gpuMs = std::numeric_limits<double>::quiet_NaN();
    } else {
        time.gpuMs = std::numeric_limits<double>::quiet_NaN();
    }
    gl::checkErrors("timing a pass");
    return time;
}

}  // namespace warplab::renderer
