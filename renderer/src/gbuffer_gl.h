// Renderer-private: the GL objects behind a GBuffer, for passes that read its attachments.
#pragma once

#include <optional>

#include "renderer/conventional.h"
#include "gl/objects.h"

namespace warplab::renderer {

struct GBuffer::Impl {
    int width = 0;
    int height = 0;
    gl::Texture colour;  // GL_RGBA8
    gl::Texture depth;  // GL_DEPTH_COMPONENT32F
    gl::Texture ids;  // GL_R32UI
    gl::Texture velocity;  // GL_RGBA32F
    gl::Framebuffer framebuffer;
    // Bidirectional reprojection's backward flow (flow_common.glsl), GL_RGBA32F, attached as a
    // fourth target only once a render asks for it; flowTo says towards which frame it points.
    gl::Texture flow;
    struct FlowTarget {
        double time = 0;
        float yaw = 0, pitch = 0;
    };
    std::optional<FlowTarget> flowTo;

    // Attachment points, matching the fragment outputs of conventional.frag.
    static constexpr GLenum kColourAttachment = GL_COLOR_ATTACHMENT0;
    static constexpr GLenum kIdAttachment = GL_COLOR_ATTACHMENT1;
    static constexpr GLenum kVelocityAttachment = GL_COLOR_ATTACHMENT2;
    static constexpr GLenum kFlowAttachment = GL_COLOR_ATTACHMENT3;
};

// A 2D texture, clamped at its edges; integer formats fetched exactly (nearest), the rest
// sampled bilinearly. Left bound to GL_TEXTURE_2D.
gl::Texture makeTexture(GLint internalFormat, GLenum format, GLenum type, int width, int height);

// Read one attachment back as a plain top-down image.
image::ImageRGBA8 readColourAttachment(const GBuffer::Impl& g);
image::ImageU32 readIdAttachment(const GBuffer::Impl& g);
image::ImageF readVectorAttachment(const GBuffer::Impl& g, int channels);  // velocity / correspondence
image::ImageF readDepthAttachment(const GBuffer::Impl& g);

}  // namespace warplab::renderer
