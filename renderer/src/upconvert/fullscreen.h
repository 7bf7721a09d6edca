// Renderer-private: a full-screen triangle for image-space passes. Core profile needs a bound
// vertex array even when the vertex shader makes its positions from gl_VertexID.
#pragma once

#include "gl/objects.h"
#include "gl/program.h"

namespace warplab::renderer {

class FullscreenPass {
public:
    FullscreenPass() : vao_(gl::VertexArray::create()) {}
    void draw() const {
        glBindVertexArray(vao_.id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glBindVertexArray(0);
    }

private:
    gl::VertexArray vao_;
};

// Binds a texture to a unit and points a sampler uniform at it.
inline void bindTexture(const gl::Program& program, const char* sampler, int unit, const gl::Texture& texture) {
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
    glBindTexture(GL_TEXTURE_2D, texture.id());
    glUniform1i(gl::uniform(program, sampler), unit);
}

// Ends an image-space pass: the first `textureUnits` units unbound, no program, the default
// framebuffer, depth testing back on -- the defaults the other passes assume.
inline void endImagePass(int textureUnits) {
    for (int unit = textureUnits - 1; unit >= 0; --unit) {
        glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
        glBindTexture(GL_TEXTURE_2D, 0);
    }
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glEnable(GL_DEPTH_TEST);
}

}  // namespace warplab::renderer
