#include "participants/perception.h"

#include <algorithm>
#include <map>
#include <cmath>
#include <limits>

#include "scene/scene.h"

namespace warplab::participants {

// ---------------------------------------------------------------------------------------------
// Perception

std::vector<SeenObject> findObjects(const image::ImageU32& ids, const image::ImageRGBA8& colour, glm::dvec2 toDisplay) {
    struct Sum {
        double x = 0.0, y = 0.0;
        glm::dvec3 colour{0.0};
        int n = 0;
    };
    std::map<std::uint32_t, Sum> sums;
    for (int y = 0; y < ids.height; ++y)
        for (int x = 0; x < ids.width; ++x) {
            const std::uint32_t id = ids.at(x, y);
            if (id < scene::kIdTarget) continue;  // hangar, sky: background
            Sum& s = sums[id];
            s.x += x + 0.5;
            s.y += y + 0.5;
            const std::uint8_t* c = colour.at(x, y);
            s.colour += glm::dvec3(c[0], c[1], c[2]) / 255.0;
            ++s.n;
        }
    std::vector<SeenObject> objects;
    for (const auto& [id, s] : sums) {
        SeenObject o;
        o.id = id;
        o.centre = glm::dvec2(s.x / s.n * toDisplay.x, s.y / s.n * toDisplay.y);
        o.radiusPx = std::sqrt(s.n * toDisplay.x * toDisplay.y / glm::pi<double>());
        o.colour = s.colour / static_cast<double>(s.n);
        o.pixels = s.n;
        objects.push_back(o);
    }
    return objects;
}

Thumbnail thumbnailOf(const image::ImageRGBA8& colour, const image::ImageU32& ids, int block, glm::dvec2 toDisplay) {
    Thumbnail t;
    t.width = colour.width / block;
    t.height = colour.height / block;
    t.cellPx = toDisplay * static_cast<double>(block);
    std::vector<float> sum(static_cast<std::size_t>(t.width) * t.height, 0.0f);
    std::vector<int> count(sum.size(), 0);
    for (int y = 0; y < t.height * block; ++y)
        for (int x = 0; x < t.width * block; ++x) {
            if (ids.at(x, y) >= scene::kIdTarget) continue;  // the scene only: objects move on their own
            const std::uint8_t* c = colour.at(x, y);
            const std::size_t cell = static_cast<std::size_t>(y / block) * t.width + x / block;
            sum[cell] += (0.299f * c[0] + 0.587f * c[1] + 0.114f * c[2]) / 255.0f;
            ++count[cell];
        }
    t.luma.resize(sum.size());
    for (std::size_t i = 0; i < sum.size(); ++i)
        t.luma[i] = count[i] > 0 ? sum[i] / count[i] : std::numeric_limits<float>::quiet_NaN();
    return t;
}

std::optional<glm::dvec2> bestShift(const Thumbnail& before, const Thumbnail& now, glm::ivec2 guess, glm::ivec2 radius,
                                    double centreShare, double minOverlapShare) {
    if (before.width != now.width || before.height != now.height || now.width < 3 || now.height < 3)
        return std::nullopt;
    const int w = now.width, h = now.height;
    // The cells of `now` compared: the central share of the picture (its edges stretch most when
    // the view turns, and hold what the turn brought into view).
    const int mx = static_cast<int>(std::lround(w * (1.0 - centreShare) * 0.5));
    const int my = static_cast<int>(std::lround(h * (1.0 - centreShare) * 0.5));
    const double minCells = minOverlapShare * (w - 2 * mx) * (h - 2 * my);
    const auto cost = [&](int sx, int sy) {
        double sum = 0.0;
        int n = 0;
        for (int y = std::max(my, sy); y < std::min(h - my, h + sy); ++y)
            for (int x = std::max(mx, sx); x < std::min(w - mx, w + sx); ++x) {
                const float a = now.at(x, y), b = before.at(x - sx, y - sy);
                if (std::isnan(a) || std::isnan(b)) continue;
                sum += (a - b) * (a - b);
                ++n;
            }
        return n >= std::max(1.0, minCells) ? sum / n : std::numeric_limits<double>::infinity();
    };
    double best = std::numeric_limits<double>::infinity();
    glm::ivec2 at = guess;
    for (int sy = guess.y - radius.y; sy <= guess.y + radius.y; ++sy)
        for (int sx = guess.x - radius.x; sx <= guess.x + radius.x; ++sx)
            if (const double c = cost(sx, sy); c < best) {
                best = c;
                at = {sx, sy};
            }
    if (!std::isfinite(best)) return std::nullopt;
    const auto refine = [&](double minus, double plus) {
        const double curvature = minus - 2.0 * best + plus;
        if (!std::isfinite(curvature) || curvature <= 1e-12) return 0.0;
        return std::clamp(0.5 * (minus - plus) / curvature, -0.5, 0.5);
    };
    return glm::dvec2(at.x + refine(cost(at.x - 1, at.y), cost(at.x + 1, at.y)),
                      at.y + refine(cost(at.x, at.y - 1), cost(at.x, at.y + 1)));
}

std::optional<glm::dvec2> whereViewIs(const Thumbnail& before, const Thumbnail& now) {
    const auto cells = bestShift(before, now, {0, 0}, {now.width / 2, now.height / 2}, 1.0, 1.0 / 3.0);
    if (!cells) return std::nullopt;
    return *cells * now.cellPx;
}

std::optional<glm::dvec2> howFarViewMoved(const Percept& before, const Percept& now, glm::dvec2 guessPx) {
    // Coarse over the blurred pictures (within a sixth of the view of the guess), then within a
    // cell of that over the sharp ones.
    const glm::ivec2 around(static_cast<int>(std::lround(guessPx.x / now.picture.cellPx.x)),
                            static_cast<int>(std::lround(guessPx.y / now.picture.cellPx.y)));
    const auto coarse =
        bestShift(before.picture, now.picture, around, {now.picture.width / 6, now.picture.height / 6}, 0.6, 0.5);
    if (!coarse) return std::nullopt;
    const glm::dvec2 ratio = now.picture.cellPx / now.detail.cellPx;
    const glm::ivec2 guess(static_cast<int>(std::lround(coarse->x * ratio.x)),
                           static_cast<int>(std::lround(coarse->y * ratio.y)));
    const glm::ivec2 radius(static_cast<int>(std::ceil(ratio.x)) + 1, static_cast<int>(std::ceil(ratio.y)) + 1);
    const auto fine = bestShift(before.detail, now.detail, guess, radius, 0.5, 0.5);
    if (!fine) return *coarse * now.picture.cellPx;
    return *fine * now.detail.cellPx;
}

}  // namespace warplab::participants
