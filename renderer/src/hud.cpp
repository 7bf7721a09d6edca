#include "renderer/hud.h"

#include <algorithm>
#include <fstream>
#include <map>

#include <SDL.h>
#include <SDL_ttf.h>

#include "gbuffer_gl.h"
#include "gl/check.h"
#include "gl/program.h"
#include "renderer/mesh.h"

namespace warplab::renderer {
namespace {

struct TextTexture {
    gl::Texture texture;
    int width = 0, height = 0;
};

}  // namespace

struct HudRenderer::Impl {
    gl::Program program;
    gl::VertexArray vao = gl::VertexArray::create();
    TTF_Font* font = nullptr;
    int fontPixels = 0;
    std::map<std::string, TextTexture> cache;  // the few strings a study shows, uploaded once

    ~Impl() {
        if (font != nullptr) TTF_CloseFont(font);
        TTF_Quit();
    }

    const TextTexture& text(const std::string& s) {
        auto it = cache.find(s);
        if (it != cache.end()) return it->second;
        SDL_Surface* rendered = TTF_RenderUTF8_Blended(font, s.c_str(), SDL_Color{255, 255, 255, 255});
        if (rendered == nullptr) throw gl::GlError(std::string("cannot draw HUD text: ") + TTF_GetError());
        SDL_Surface* rgba = SDL_ConvertSurfaceFormat(rendered, SDL_PIXELFORMAT_RGBA32, 0);
        SDL_FreeSurface(rendered);
        if (rgba == nullptr) throw gl::GlError(std::string("cannot convert HUD text: ") + SDL_GetError());
        TextTexture t;
        t.width = rgba->w;
        t.height = rgba->h;
        t.texture = gl::Texture::create();
        glBindTexture(GL_TEXTURE_2D, t.texture.id());
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glPixelStorei(GL_UNPACK_ROW_LENGTH, rgba->pitch / 4);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, t.width, t.height, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba->pixels);
        glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        SDL_FreeSurface(rgba);
        gl::checkErrors("uploading HUD text");
        return cache.emplace(s, std::move(t)).first->second;
    }

    // `text` broken into lines no wider than `widthPixels` at `scale` of the font's size:
    // at spaces, and at every line break it has. A word wider than the line keeps a line of
    // its own.
    std::vector<std::string> wrapped(const std::string& text, float widthPixels, float scale) {
        std::vector<std::string> lines;
        auto fits = [&](const std::string& line) {
            int w = 0, h = 0;
            return TTF_SizeUTF8(font, line.c_str(), &w, &h) == 0 && w * scale <= widthPixels;
        };
        std::size_t start = 0;
        while (start <= text.size()) {
            const std::size_t end = std::min(text.find('\n', start), text.size());
            std::string line;
            std::size_t at = start;
            while (at < end) {
                const std::size_t space = std::min(text.find(' ', at), end);
                const std::string word = text.substr(at, space - at);
                const std::string longer = line.empty() ? word : line + " " + word;
                if (!line.empty() && !fits(longer)) {
                    lines.push_back(line);
                    line = word;
                } else {
                    line = longer;
                }
                at = space + 1;
            }
            lines.push_back(line);
            start = end + 1;
        }
        return lines;
    }

    void rect(float x, float y, float w, float h, const float colour[4]) {
        glUniform4f(gl::uniform(program, "uRect"), x, y, w, h);
        glUniform4f(gl::uniform(program, "uColour"), colour[0], colour[1], colour[2], colour[3]);
        glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    }
};

HudRenderer::HudRenderer(const DataPaths& paths, const std::string& fontPath) : impl_(std::make_unique<Impl>()) {
    if (!std::ifstream(fontPath))
        throw AssetError("cannot read HUD font '" + fontPath + "' (install fonts-dejavu-core)");
    if (TTF_Init() != 0) throw AssetError(std::string("cannot start SDL2_ttf: ") + TTF_GetError());
    impl_->program =
        gl::buildProgram({paths.shaderDir, {{GL_VERTEX_SHADER, "hud.vert"}, {GL_FRAGMENT_SHADER, "hud.frag"}}, {}});
    fontPath_ = fontPath;  // opened on first draw, at a size that follows the frame height
}

HudRenderer::~HudRenderer() = default;

void HudRenderer::draw(const HudContent& content, GBuffer& target) {
    auto& m = *impl_;
    auto& g = target.impl();
    const int w = g.width, h = g.height;
    // Text scales with the frame: 1/12 of the height for the banner, 1/28 for the status line.
    const int bannerPixels = std::max(8, h / 12);
    if (m.font == nullptr || m.fontPixels != bannerPixels) {
        if (m.font != nullptr) TTF_CloseFont(m.font);
        m.cache.clear();
        m.font = TTF_OpenFont(fontPath_.c_str(), bannerPixels);
        if (m.font == nullptr) throw AssetError("cannot load HUD font '" + fontPath_ + "': " + TTF_GetError());
        m.fontPixels = bannerPixels;
    }

    glBindFramebuffer(GL_FRAMEBUFFER, g.framebuffer.id());
    const GLenum colourOnly[3] = {GBuffer::Impl::kColourAttachment, GL_NONE, GL_NONE};
    glDrawBuffers(3, colourOnly);
    glViewport(0, 0, w, h);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(m.program.id());
    glUniform2f(gl::uniform(m.program, "uViewport"), static_cast<float>(w), static_cast<float>(h));
    glBindVertexArray(m.vao.id());

    const float dark[4] = {0.0f, 0.0f, 0.0f, 0.6f}, light[4] = {1.0f, 1.0f, 1.0f, 0.9f};
    glUniform1i(gl::uniform(m.program, "uTextured"), 0);
    if (content.backdrop) {
        const float backdrop[4] = {0.12f, 0.13f, 0.16f, 1.0f};
        m.rect(0.0f, 0.0f, static_cast<float>(w), static_cast<float>(h), backdrop);
    }
    if (content.reticle) {
        // A cross with a dark outline so it reads on light and dark walls alike.
        const float arm = std::max(3.0f, h / 60.0f), thick = std::max(1.0f, h / 360.0f);
        const float cx = w * 0.5f, cy = h * 0.5f;
        m.rect(cx - arm - 1, cy - thick / 2 - 1, 2 * arm + 2, thick + 2, dark);
        m.rect(cx - thick / 2 - 1, cy - arm - 1, thick + 2, 2 * arm + 2, dark);
        m.rect(cx - arm, cy - thick / 2, 2 * arm, thick, light);
        m.rect(cx - thick / 2, cy - arm, thick, 2 * arm, light);
    }
    auto drawText = [&](const std::string& s, float centreX, float baselineY, float scale, const float colour[4],
                        bool fitWidth = false) {
        const TextTexture& t = m.text(s);
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, t.texture.id());
        glUniform1i(gl::uniform(m.program, "uText"), 0);
        glUniform1i(gl::uniform(m.program, "uTextured"), 1);
        // A status line wider than the frame (a long refusal on a small window) is drawn
        // smaller, so that all of it shows rather than its middle.
        if (fitWidth) scale = std::min(scale, 0.98f * static_cast<float>(w) / static_cast<float>(std::max(1, t.width)));
        const float tw = t.width * scale, th = t.height * scale;
        m.rect(centreX - tw / 2, baselineY, tw, th, colour);
    };
    if (content.question) {
        const HudQuestion& r = *content.question;
        const float white[4] = {0.95f, 0.95f, 0.95f, 1.0f}, grey[4] = {0.8f, 0.8f, 0.8f, 0.9f};
        const float fill[4] = {0.25f, 0.27f, 0.33f, 1.0f}, lit[4] = {0.35f, 0.55f, 0.85f, 1.0f};
        if (!r.prompt.empty()) drawText(r.prompt, w * 0.5f, h * 0.62f, 0.55f, white);
        for (std::size_t i = 0; i < r.boxes.size(); ++i) {
            const glm::vec4 b = r.boxes[i];
            const float y = h - b.y - b.w;  // frame pixels are y-down; GL is y-up
            glUniform1i(gl::uniform(m.program, "uTextured"), 0);
            m.rect(b.x - 2, y - 2, b.z + 4, b.w + 4, light);
            m.rect(b.x, y, b.z, b.w, static_cast<int>(i) == r.highlighted ? lit : fill);
            drawText(std::to_string(r.firstValue + static_cast<int>(i)), b.x + b.z * 0.5f, y + b.w * 0.2f, 0.6f, white);
        }
        if (!r.boxes.empty()) {
            const glm::vec4 first = r.boxes.front(), last = r.boxes.back();
            if (!r.minLabel.empty())
                drawText(r.minLabel, first.x + first.z * 0.5f, h - first.y - first.w - h * 0.06f, 0.3f, grey);
            if (!r.maxLabel.empty())
                drawText(r.maxLabel, last.x + last.z * 0.5f, h - last.y - last.w - h * 0.06f, 0.3f, grey);
        }
    }
    if (!content.paragraph.empty()) {
        const float white[4] = {0.95f, 0.95f, 0.95f, 1.0f};
        const float scale = 0.45f, lineHeight = bannerPixels * scale * 1.4f;
        const std::vector<std::string> lines = m.wrapped(content.paragraph, w * 0.8f, scale);
        // Centred on the screen as a block, top to bottom (GL is y-up).
        float y = h * 0.5f + lines.size() * lineHeight * 0.5f - lineHeight;
        for (const std::string& line : lines) {
            if (!line.empty()) drawText(line, w * 0.5f, y, scale, white);
            y -= lineHeight;
        }
    }
    if (content.cursor) {
        // A small cross with a dark outline, centred on the cursor's pixel.
        const float arm = std::max(3.0f, h / 90.0f), thick = std::max(1.0f, h / 400.0f);
        const float cx = content.cursor->x, cy = h - content.cursor->y;
        glUniform1i(gl::uniform(m.program, "uTextured"), 0);
        m.rect(cx - arm - 1, cy - thick / 2 - 1, 2 * arm + 2, thick + 2, dark);
        m.rect(cx - thick / 2 - 1, cy - arm - 1, thick + 2, 2 * arm + 2, dark);
        m.rect(cx - arm, cy - thick / 2, 2 * arm, thick, light);
        m.rect(cx - thick / 2, cy - arm, thick, 2 * arm, light);
    }
    if (!content.banner.empty()) {
        const float green[4] = {0.2f, 0.95f, 0.3f, 1.0f}, red[4] = {1.0f, 0.2f, 0.15f, 1.0f};
        drawText(content.banner, w * 0.5f, h * 0.58f, 1.0f, content.bannerGood ? green : red);
    }
    if (!content.status.empty()) {
        const float grey[4] = {0.9f, 0.9f, 0.9f, 0.85f};
        drawText(content.status, w * 0.5f, h * 0.93f, 0.4f, grey, true);
    }

    glBindVertexArray(0);
    glUseProgram(0);
    glDisable(GL_BLEND);
    const GLenum all[3] = {GBuffer::Impl::kColourAttachment, GBuffer::Impl::kIdAttachment,
                           GBuffer::Impl::kVelocityAttachment};
    glDrawBuffers(3, all);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glEnable(GL_DEPTH_TEST);
    gl::checkErrors("drawing the HUD");
}

}  // namespace warplab::renderer
