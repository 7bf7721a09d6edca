#include "gl/check.h"

namespace warplab::gl {

const char* errorName(GLenum error) {
    switch (error) {
        case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
        case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
        case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
        default: return "unknown GL error";
    }
}

void checkErrors(const char* what) {
    std::string names;
    // glGetError returns one flag per call; bound the loop in case a broken context never
    // clears its flag.
    for (int i = 0; i < 16; ++i) {
        const GLenum error = glGetError();
        if (error == GL_NO_ERROR) break;
        if (!names.empty()) names += ", ";
        names += errorName(error);
    }
    if (!names.empty()) throw GlError(std::string("OpenGL error while ") + what + ": " + names);
}

}  // namespace warplab::gl
