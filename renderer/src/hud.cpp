#include "renderer/hud.h"

#include <algorithm>
#include <cmath>
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
    int frameHeight = 0;  // of the frame being drawn over
    // The least font size text is drawn at, pixels: a line a participant can read at 320 x 180.
    static constexpr float kMinTextPixels = 9.0f;
    // The strings shown, uploaded once: a study's few fixed ones, and each state of an answer
    // being typed, which is why the cache is bounded.
    std::map<std::string, TextTexture> cache;
    static constexpr std::size_t kCachedTexts = 256;

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
        if (cache.size() >= kCachedTexts) cache.clear();  // the fixed strings come back at once
        return cache.emplace(s, std::move(t)).first->second;
    }

    // Width of `s` as drawn at `scale`, pixels (its texture's: what centring needs).
    float widthAt(const std::string& s, float scale) { return s.empty() ? 0.0f : text(s).width * scale; }
    // Width of `s` at the font's size, pixels, measured without drawing it.
    int widthOf(const std::string& s) const {
        int w = 0, h = 0;
        return s.empty() || TTF_SizeUTF8(font, s.c_str(), &w, &h) != 0 ? 0 : w;
    }

    // Draws `s` with its bottom-left corner at (left, bottom), GL pixels (y up); returns the
    // width drawn. The uniforms are the untextured rectangles' again afterwards.
    float textAt(const std::string& s, float left, float bottom, float scale, const float colour[4]) {
        if (s.empty()) return 0.0f;  // SDL2_ttf draws no empty string
        const TextTexture& t = text(s);
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, t.texture.id());
        glUniform1i(gl::uniform(program, "uText"), 0);
        glUniform1i(gl::uniform(program, "uTextured"), 1);
        rect(left, bottom, t.width * scale, t.height * scale, colour);
        glUniform1i(gl::uniform(program, "uTextured"), 0);
        return t.width * scale;
    }

    // The end of `s` that fits in `widthPixels` at `scale`, after an ellipsis when some of its
    // start is left out: a long answer shows what is being typed.
    std::string tailThatFits(const std::string& s, float widthPixels, float scale) const {
        const float room = widthPixels / scale;
        if (widthOf(s) <= room) return s;
        static const std::string kEllipsis = "\u2026";
        std::vector<std::size_t> starts;  // where each UTF-8 character begins
        for (std::size_t i = 0; i < s.size(); ++i)
            if ((static_cast<unsigned char>(s[i]) & 0xC0) != 0x80) starts.push_back(i);
        // The fewest characters left out (a longer tail is never narrower).
        std::size_t lo = 1, hi = starts.size();  // hi: nothing left but the ellipsis
        while (lo < hi) {
            const std::size_t mid = (lo + hi) / 2;
            if (widthOf(kEllipsis + s.substr(starts[mid])) <= room)
                hi = mid;
            else
                lo = mid + 1;
        }
        return hi < starts.size() ? kEllipsis + s.substr(starts[hi]) : kEllipsis;
    }

    void question(const HudQuestion& q, int w, int h);

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

    // `scale` of the font's size, or more where that would draw text under kMinTextPixels:
    // text scales with the frame, and on a small one (320 x 180) a fraction of it is a smudge.
    // Frames smaller still (a test's 160 x 90) keep a twentieth of their height, so that a
    // screen's lines still fit in it.
    float readable(float scale) const {
        const float least = std::min(kMinTextPixels, static_cast<float>(frameHeight) / 20.0f);
        return std::max(scale, std::min(1.0f, least / static_cast<float>(std::max(1, fontPixels))));
    }

    // `s` wrapped to `widthPixels` at `scale` and drawn line under line, the first line's top at
    // `top` (GL pixels, y up), each line placed by `align` (-1 left from x, 0 centred on x, 1
    // right to x). Returns the bottom of the last line.
    float lines(const std::string& s, float x, float top, float widthPixels, float scale, int align,
                const float colour[4]) {
        const float lineHeight = static_cast<float>(TTF_FontHeight(font)) * scale;
        float bottom = top;
        for (const std::string& line : wrapped(s, widthPixels, scale)) {
            bottom -= lineHeight;
            const float width = widthAt(line, scale);
            textAt(line, align < 0 ? x : align > 0 ? x - width : x - width / 2, bottom, scale, colour);
        }
        return bottom;
    }

    void rect(float x, float y, float w, float h, const float colour[4]) {
        glUniform4f(gl::uniform(program, "uRect"), x, y, w, h);
        glUniform4f(gl::uniform(program, "uColour"), colour[0], colour[1], colour[2], colour[3]);
        glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    }
};

void HudRenderer::Impl::question(const HudQuestion& q, int w, int h) {
    const float white[4] = {0.95f, 0.95f, 0.95f, 1.0f}, grey[4] = {0.8f, 0.8f, 0.8f, 0.9f};
    const float light[4] = {1.0f, 1.0f, 1.0f, 0.9f};
    const float fill[4] = {0.25f, 0.27f, 0.33f, 1.0f}, lit[4] = {0.35f, 0.55f, 0.85f, 1.0f};
    const float lineHeight = static_cast<float>(TTF_FontHeight(font));  // pixels at scale 1

    // The prompt above the boxes: where the rating screen always had it (its last line), or
    // higher when the game's boxes reach above that (a list of options), clear of the status
    // line. A prompt wider than the frame wraps rather than shrinks.
    float top = 0.0f;  // the boxes' top edge, GL pixels (y up)
    for (const glm::vec4& b : q.boxes) top = std::max(top, h - b.y);
    if (!q.prompt.empty()) {
        const float scale = readable(0.55f), room = 0.94f * static_cast<float>(w);
        const float bottom = std::min(std::max(h * 0.62f, top + h * 0.08f), h * 0.84f);
        const auto rows = static_cast<float>(wrapped(q.prompt, room, scale).size());
        lines(q.prompt, w * 0.5f, bottom + rows * lineHeight * scale, room, scale, 0, white);
    }

    float below = static_cast<float>(h);  // the lowest edge drawn under the boxes so far
    for (std::size_t i = 0; i < q.boxes.size(); ++i) {
        const glm::vec4 b = q.boxes[i];
        const float x = b.x, y = h - b.y - b.w, bw = b.z, bh = b.w;  // frame pixels are y-down; GL is y-up
        below = std::min(below, y - 2);
        rect(x - 2, y - 2, bw + 4, bh + 4, light);
        rect(x, y, bw, bh, static_cast<int>(i) == q.highlighted ? lit : fill);
        const std::string label = i < q.boxLabels.size() ? q.boxLabels[i] : std::string();
        switch (q.kind) {
            case HudQuestion::Kind::Likert:
                textAt(label, x + (bw - widthAt(label, 0.6f)) * 0.5f, y + bh * 0.2f, 0.6f, white);
                break;
            case HudQuestion::Kind::Choice: {
                // Its number in a column of its own, then the option, shrunk only if it is
                // wider than what is left of the box.
                const float pad = std::max(2.0f, bh * 0.25f), scale = std::min(0.45f, 0.7f * bh / lineHeight);
                const float bottom = y + (bh - lineHeight * scale) * 0.5f;
                textAt(std::to_string(i + 1), x + pad, bottom, scale, white);
                const float left = x + pad + widthOf("9  ") * scale, room = x + bw - pad - left;
                if (!label.empty()) textAt(label, left, bottom, std::min(scale, room / widthAt(label, 1.0f)), white);
                break;
            }
            case HudQuestion::Kind::Text: {
                // What was typed, its end when it is wider than the field, then the caret.
                const float pad = std::max(2.0f, bh * 0.2f), scale = std::min(0.45f, 0.65f * bh / lineHeight);
                const float caretW = std::max(1.0f, h / 300.0f), textH = lineHeight * scale;
                const float bottom = y + (bh - textH) * 0.5f;
                const float drawn =
                    textAt(tailThatFits(q.typed, bw - 2 * pad - 2 * caretW, scale), x + pad, bottom, scale, white);
                rect(x + pad + drawn + caretW * 0.5f, bottom + textH * 0.1f, caretW, textH * 0.8f, white);
                break;
            }
        }
    }
    const float gap = h * 0.02f, small = readable(0.4f);
    if (q.kind == HudQuestion::Kind::Likert && !q.boxes.empty()) {
        // Under the ends of the row, flush with its outer edges so that neither leaves the
        // frame, each wrapped to its half of the row (a long label on a small display).
        const glm::vec4 first = q.boxes.front(), last = q.boxes.back();
        const float left = first.x, right = last.x + last.z, half = std::max(right - left, w * 0.5f) * 0.48f;
        const float labelsTop = below - gap;
        float bottom = labelsTop;
        if (!q.minLabel.empty()) bottom = std::min(bottom, lines(q.minLabel, left, labelsTop, half, small, -1, grey));
        if (!q.maxLabel.empty()) bottom = std::min(bottom, lines(q.maxLabel, right, labelsTop, half, small, 1, grey));
        below = bottom;
    }
    // How to answer, under everything else.
    if (!q.hint.empty()) lines(q.hint, w * 0.5f, below - gap, 0.94f * static_cast<float>(w), small, 0, grey);
}

int HudPhotonMarker::sidePixels(int frameWidth, int frameHeight) {
    const int side = std::max(16, static_cast<int>(std::lround(frameHeight * 0.04)));
    return std::min(side, std::min(frameWidth, frameHeight));
}

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
    m.frameHeight = h;
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
    auto drawText = [&](const std::string& s, float centreX, float baselineY, float scale, const float colour[4]) {
        m.textAt(s, centreX - m.widthAt(s, scale) / 2, baselineY, scale, colour);
    };
    if (content.question) m.question(*content.question, w, h);
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
        // A status line wider than the frame (the start screen's, a refusal, on a small
        // window) wraps downwards from where one line sits, so that all of it shows, readable.
        const float scale = m.readable(0.4f);
        const float top = h * 0.93f + static_cast<float>(TTF_FontHeight(m.font)) * scale;
        m.lines(content.status, w * 0.5f, std::min(top, static_cast<float>(h)), 0.96f * static_cast<float>(w), scale, 0,
                grey);
    }

    if (content.photonMarker) {
        // Last and unblended: exactly black or white, whatever is under it.
        glDisable(GL_BLEND);
        const HudPhotonMarker& marker = *content.photonMarker;
        using Corner = HudPhotonMarker::Corner;
        const int side = HudPhotonMarker::sidePixels(w, h);
        const bool left = marker.corner == Corner::TopLeft || marker.corner == Corner::BottomLeft;
        const bool top = marker.corner == Corner::TopLeft || marker.corner == Corner::TopRight;
        const float black[4] = {0.0f, 0.0f, 0.0f, 1.0f}, white[4] = {1.0f, 1.0f, 1.0f, 1.0f};
        m.rect(static_cast<float>(left ? 0 : w - side), static_cast<float>(top ? h - side : 0),
               static_cast<float>(side), static_cast<float>(side), marker.lit ? white : black);
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
