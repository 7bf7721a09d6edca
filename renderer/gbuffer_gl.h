// Renderer-private: the GL objects behind a GBuffer, for passes that read its attachments.
#pragma once

#include "renderer/conventional.h"
#include "renderer/gl/objects.h"

namespace warplab::renderer {

struct GBuffer::Impl {
    int width = 0;
    int height = 0;
    gl::Texture colour;    // GL_RGBA8
    gl::Texture depth;     // GL_DEPTH_COMPONENT32F
    gl::Texture ids;       // GL_R32UI
    gl::Texture velocity;  // GL_RGBA32F
    gl::Framebuffer framebuffer;

    // Attachment points, matching the fragment outputs of conventional.frag.
    static constexpr GLenum kColourAttachment = GL_COLOR_ATTACHMENT0;
    static constexpr GLenum kIdAttachment = GL_COLOR_ATTACHMENT1;
    static constexpr GLenum kVelocityAttachment = GL_COLOR_ATTACHMENT2;
};

// Read one attachment back as a plain top-down image.
ImageRGBA8 readColourAttachment(const GBuffer::Impl& g);
ImageU32 readIdAttachment(const GBuffer::Impl& g);
ImageF readVectorAttachment(const GBuffer::Impl& g, int channels);  // velocity / correspondence
ImageF readDepthAttachment(const GBuffer::Impl& g);

}  // namespace warplab::renderer
