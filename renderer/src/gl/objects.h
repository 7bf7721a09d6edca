// Move-only owners for every kind of OpenGL object, after Magnum's GL wrappers: copy is
// deleted, move is noexcept, the destructor deletes the object, and a default-constructed
// owner is empty and needs no context. Nothing outside this file calls glGen*/glDelete*.
//
// Owners must be destroyed while their context is still current: keep the GlContext alive
// longer than every renderer that holds these.
#pragma once

#include <utility>

#include "gl/api.h"

namespace warplab::gl {

template <typename Traits>
class Object {
public:
    Object() noexcept = default;
    template <typename... Args>
    static Object create(Args... args) {
        return Object(Traits::create(args...));
    }
    ~Object() { reset(); }

    Object(const Object&) = delete;
    Object& operator=(const Object&) = delete;
    Object(Object&& other) noexcept : id_(std::exchange(other.id_, 0u)) {}
    Object& operator=(Object&& other) noexcept {
        if (this != &other) {
            reset();
            id_ = std::exchange(other.id_, 0u);
        }
        return *this;
    }

    GLuint id() const noexcept { return id_; }
    explicit operator bool() const noexcept { return id_ != 0; }
    void reset() noexcept {
        if (id_ != 0) Traits::destroy(id_);
        id_ = 0;
    }

private:
    explicit Object(GLuint id) noexcept : id_(id) {}
    GLuint id_ = 0;
};

namespace traits {
#define WARPLAB_GL_GEN_TRAITS(Name, gen, del)                    \
    struct Name {                                                \
        static GLuint create() {                                 \
            GLuint id = 0;                                       \
            gen(1, &id);                                         \
            return id;                                           \
        }                                                        \
        static void destroy(GLuint id) noexcept { del(1, &id); } \
    };
WARPLAB_GL_GEN_TRAITS(Buffer, glGenBuffers, glDeleteBuffers)
WARPLAB_GL_GEN_TRAITS(VertexArray, glGenVertexArrays, glDeleteVertexArrays)
WARPLAB_GL_GEN_TRAITS(Texture, glGenTextures, glDeleteTextures)
WARPLAB_GL_GEN_TRAITS(Renderbuffer, glGenRenderbuffers, glDeleteRenderbuffers)
WARPLAB_GL_GEN_TRAITS(Framebuffer, glGenFramebuffers, glDeleteFramebuffers)
WARPLAB_GL_GEN_TRAITS(Query, glGenQueries, glDeleteQueries)
#undef WARPLAB_GL_GEN_TRAITS

struct Shader {
    static GLuint create(GLenum stage) { return glCreateShader(stage); }
    static void destroy(GLuint id) noexcept { glDeleteShader(id); }
};
struct Program {
    static GLuint create() { return glCreateProgram(); }
    static void destroy(GLuint id) noexcept { glDeleteProgram(id); }
};
}  // namespace traits

using Buffer = Object<traits::Buffer>;
using VertexArray = Object<traits::VertexArray>;
using Texture = Object<traits::Texture>;
using Renderbuffer = Object<traits::Renderbuffer>;
using Framebuffer = Object<traits::Framebuffer>;
using Query = Object<traits::Query>;
using Shader = Object<traits::Shader>;
using Program = Object<traits::Program>;

}  // namespace warplab::gl
