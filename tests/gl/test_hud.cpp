// The HUD draws over colour only: the reticle at the centre or the cursor where it is, the
// banner in its colour, the question screens of each kind, and the object ids untouched (the
// pointer's id cross-check reads them).
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "gl/gl_test_support.h"
#include "renderer/hud.h"
#include "renderer/mesh.h"

namespace warplab {
namespace {

constexpr int kW = 320;
constexpr int kH = 180;

// The frame every HUD test draws over: the hallway with the target, rendered.
testing::RenderedSource hallwayWithTarget() {
    const auto shooter = testing::shooterScene(kW, kH, 2);
    return testing::renderSource({shooter.restingCamera(), shooter.snapshot(0.5)}, kW, kH);
}

TEST(Hud, ReticleAndBannerOverColourIdsUntouched) {
    auto source = hallwayWithTarget();
    renderer::HudRenderer hud(testing::sourceDataPaths());
    renderer::HudContent content;
    content.banner = "HIT";
    content.bannerGood = true;
    content.status = "Training: level 3";
    hud.draw(content, source.frame->gbuffer);
    const auto after = renderer::readBack(source.frame->gbuffer);

    EXPECT_EQ(after.ids.data, source.images.ids.data);
    const std::uint8_t* centre = after.colour.at(kW / 2, kH / 2);
    EXPECT_GT(centre[0], 200);  // the reticle's light cross
    EXPECT_GT(centre[1], 200);
    int green = 0;
    for (int y = 0; y < kH / 2; ++y)
        for (int x = 0; x < kW; ++x) {
            const std::uint8_t* p = after.colour.at(x, y);
            green += p[1] > 180 && p[0] < 120 && p[2] < 120;
        }
    EXPECT_GT(green, 50) << "no green HIT banner in the upper half";
    int changed = 0;
    for (std::size_t i = 0; i < after.colour.pixels.size(); ++i)
        changed += after.colour.pixels[i] != source.images.colour.pixels[i];
    EXPECT_LT(changed, static_cast<int>(after.colour.pixels.size() / 10)) << "the HUD should cover little of the frame";
}

// The click game's cursor lands on the pixel it names (y down, like the images), not at the
// centre; the ids under it stay the scene's.
TEST(Hud, CursorIsDrawnWhereItIs) {
    auto source = hallwayWithTarget();
    renderer::HudRenderer hud(testing::sourceDataPaths());
    renderer::HudContent content;
    content.reticle = false;
    content.cursor = glm::vec2(60.5f, 40.5f);
    hud.draw(content, source.frame->gbuffer);
    const auto after = renderer::readBack(source.frame->gbuffer);
    EXPECT_EQ(after.ids.data, source.images.ids.data);
    const std::uint8_t* at = after.colour.at(60, 40);
    EXPECT_GT(at[0], 200);
    EXPECT_GT(at[1], 200);
    EXPECT_GT(at[2], 200);
    // Nothing at the centre (no reticle) or at the mirrored row (y is not flipped).
    EXPECT_EQ(std::vector<std::uint8_t>(after.colour.at(kW / 2, kH / 2), after.colour.at(kW / 2, kH / 2) + 4),
              std::vector<std::uint8_t>(source.images.colour.at(kW / 2, kH / 2),
                                        source.images.colour.at(kW / 2, kH / 2) + 4));
    const std::uint8_t* mirrored = after.colour.at(60, kH - 1 - 40);
    const std::uint8_t* before = source.images.colour.at(60, kH - 1 - 40);
    EXPECT_TRUE(mirrored[0] == before[0] && mirrored[1] == before[1] && mirrored[2] == before[2]);
}

// A rating screen: a dark backdrop over everything, the highlighted box in blue, the others
// in slate, each where the game put it.
TEST(Hud, RatingScreenDrawsTheBoxesWhereTheGamePutThem) {
    auto source = hallwayWithTarget();
    renderer::HudRenderer hud(testing::sourceDataPaths());
    renderer::HudContent content;
    content.backdrop = true;
    content.reticle = false;
    renderer::HudQuestion rating;
    rating.prompt = "The animation was smooth";
    for (int i = 0; i < 7; ++i) {
        rating.boxes.emplace_back(40.0f + i * 36.0f, 100.0f, 24.0f, 24.0f);
        rating.boxLabels.push_back(std::to_string(i + 1));
    }
    rating.highlighted = 2;
    rating.minLabel = "strongly disagree";
    rating.maxLabel = "strongly agree";
    content.question = rating;
    hud.draw(content, source.frame->gbuffer);
    const auto after = renderer::readBack(source.frame->gbuffer);
    auto blueish = [&](int x, int y) {
        const std::uint8_t* p = after.colour.at(x, y);
        return p[2] > 180 && p[0] < 120;
    };
    // Inside box 2 near its corner (clear of the digit): lit; inside box 3: not.
    EXPECT_TRUE(blueish(40 + 2 * 36 + 3, 100 + 3));
    EXPECT_FALSE(blueish(40 + 3 * 36 + 3, 100 + 3));
    // The backdrop covers the scene: a corner far from the boxes is the backdrop's colour.
    const std::uint8_t* corner = after.colour.at(2, 170);
    EXPECT_LT(std::abs(corner[0] - 31), 3);
    EXPECT_LT(std::abs(corner[2] - 41), 3);
}

// The question screens as a person approved them (scripts/approve-references.sh): a list of
// options and a field of typed text. Over the opaque backdrop, so only the HUD is compared.
// The glyphs are FreeType's coverage of the DejaVu font, the same bytes wherever the same
// FreeType draws them; what another rasteriser may change is its bilinear filtering of them at
// a fraction of their size, a few levels at a glyph's edge. So the mean stays the GL tests'
// (gl_test_support.h), but no pixel share is allowed over 24 levels beyond a few edge pixels:
// the shading's silhouette allowance (0.4 %, some 230 pixels here) would pass a missing digit
// or a changed letter, which is some 10 to 20 pixels.
testing::ImageThresholds hudThresholds() {
    testing::ImageThresholds t;
    t.maxShareOver = 0.0001;  // 5 pixels of 320 x 180
    return t;
}

renderer::HudContent questionScreen(const renderer::HudQuestion& question) {
    renderer::HudContent content;
    content.backdrop = true;
    content.reticle = false;
    content.status = "Match 3 of 14: a few questions about it";
    content.question = question;
    return content;
}

image::ImageRGBA8 drawn(const renderer::HudContent& content) {
    auto source = hallwayWithTarget();
    renderer::HudRenderer hud(testing::sourceDataPaths());
    hud.draw(content, source.frame->gbuffer);
    return renderer::readBack(source.frame->gbuffer).colour;
}

// The fill of a box, read near its right edge, clear of any text: (r, g, b).
std::vector<int> fillAt(const image::ImageRGBA8& image, int x, int y) {
    const std::uint8_t* p = image.at(x, y);
    return {p[0], p[1], p[2]};
}

// Pixels in the rectangle [x0, x1) x [y0, y1) (y down) as bright as text is.
int brightIn(const image::ImageRGBA8& image, int x0, int y0, int x1, int y1) {
    int bright = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const std::uint8_t* p = image.at(x, y);
            bright += p[0] > 150 && p[1] > 150 && p[2] > 150;
        }
    return bright;
}

renderer::HudQuestion choiceQuestion() {
    renderer::HudQuestion q;
    q.kind = renderer::HudQuestion::Kind::Choice;
    q.prompt = "Which match felt smoother?";
    q.boxLabels = {"The first one", "The second one", "No difference", "I could not tell"};
    for (int i = 0; i < 4; ++i) q.boxes.emplace_back(70.0f, 62.0f + i * 26.0f, 180.0f, 20.0f);
    q.highlighted = 1;
    q.minLabel = "strongly disagree";  // a scale's: a choice does not show them
    return q;
}

TEST(Hud, ChoiceScreenMatchesReference) {
    const renderer::HudQuestion q = choiceQuestion();
    const image::ImageRGBA8 image = drawn(questionScreen(q));
    EXPECT_TRUE(testing::matchesReference("hud_choice", image, hudThresholds()));
    // The highlighted option lit, the others not (read at the boxes' right end, past their text).
    const std::vector<int> lit{89, 140, 217}, fill{64, 69, 84};
    EXPECT_EQ(fillAt(image, 245, 62 + 26 + 10), lit);
    EXPECT_EQ(fillAt(image, 245, 62 + 10), fill);
    // Each box holds its number and its option, left-aligned: text in its left part, none
    // between the boxes or past their right end.
    for (int i = 0; i < 4; ++i) {
        const int top = 62 + i * 26;
        EXPECT_GT(brightIn(image, 72, top + 2, 81, top + 18), 2) << "no number in box " << i;
        EXPECT_GT(brightIn(image, 84, top + 2, 160, top + 18), 20) << "no option in box " << i;
    }
    EXPECT_EQ(brightIn(image, 0, 62, 68, 62 + 4 * 26), 0) << "text left of the list";
    EXPECT_EQ(brightIn(image, 252, 62, kW, 62 + 4 * 26), 0) << "text right of the list";
    EXPECT_EQ(brightIn(image, 0, 62 + 4 * 26, kW, kH), 0) << "end labels under a choice";
}

renderer::HudQuestion textQuestion(const std::string& typed) {
    renderer::HudQuestion q;
    q.kind = renderer::HudQuestion::Kind::Text;
    q.prompt = "How did the motion look?";
    q.boxes = {{40.0f, 84.0f, 240.0f, 24.0f}};
    q.typed = typed;
    q.hint = "Type your answer, then press Enter";
    return q;
}

// An answer longer than the field.
std::string longAnswer() {
    std::string longer;
    for (int i = 0; i < 6; ++i) longer += "the spheres stuttered when they bounced, ";
    return longer + "but only then";
}

TEST(Hud, TextScreenMatchesReference) {
    const image::ImageRGBA8 image = drawn(questionScreen(textQuestion("smooth, but laggy \xE2\x80\x94 ok")));
    EXPECT_TRUE(testing::matchesReference("hud_text", image, hudThresholds()));
    EXPECT_GT(brightIn(image, 44, 88, 160, 104), 60) << "no typed text at the field's left";
    EXPECT_EQ(brightIn(image, 200, 86, 278, 106), 0) << "the short answer should leave the field's end empty";
    EXPECT_TRUE(
        testing::matchesReference("hud_text_long", drawn(questionScreen(textQuestion(longAnswer()))), hudThresholds()));
}

// A long answer shows its end, the part being typed, and nothing of it leaves the field.
TEST(Hud, LongTypedTextShowsItsEndInsideTheField) {
    const image::ImageRGBA8 image = drawn(questionScreen(textQuestion(longAnswer())));
    // The field spans x 40..280 and y 84..108; its light outline is 2 px around it.
    EXPECT_EQ(brightIn(image, 0, 84, 37, 108), 0) << "text spills left of the field";
    EXPECT_EQ(brightIn(image, 283, 84, kW, 108), 0) << "text spills right of the field";
    // Its end, not its start: dots, then heavy letters; the field shows letters across.
    const image::ImageRGBA8 ink = drawn(questionScreen(textQuestion(std::string(300, '.') + std::string(40, 'M'))));
    EXPECT_GT(brightIn(ink, 60, 88, 260, 104), 400) << "the start of the answer is shown, not its end";
}

// The rows [y0, y1) (y down) that hold ink as bright as text in the columns [x0, x1): runs of
// such rows, each one line of text, as (first row, rows).
std::vector<std::pair<int, int>> textRowsIn(const image::ImageRGBA8& image, int x0, int y0, int x1, int y1) {
    std::vector<std::pair<int, int>> runs;
    for (int y = y0; y < y1; ++y) {
        if (brightIn(image, x0, y, x1, y + 1) == 0) continue;
        if (!runs.empty() && runs.back().first + runs.back().second == y)
            ++runs.back().second;
        else
            runs.emplace_back(y, 1);
    }
    return runs;
}

// A Likert screen as the games lay one out at 320 x 180 (seven boxes of 18 px across the
// middle): no box lit when none is under the cursor, the end labels at a readable size under
// the row's outer edges, and a line under everything saying how to answer.
TEST(Hud, ALikertScreenAt320x180SaysHowToAnswerInReadableText) {
    renderer::HudQuestion q;
    q.prompt = "The motion looked smooth";
    for (int i = 0; i < 7; ++i) {
        q.boxes.emplace_back(70.0f + i * 27.0f, 90.0f, 18.0f, 18.0f);
        q.boxLabels.push_back(std::to_string(i + 1));
    }
    q.minLabel = "strongly disagree";
    q.maxLabel = "strongly agree";
    q.hint = "Click a box, or press 1\u20137, to answer";
    renderer::HudContent content;
    content.backdrop = true;
    content.reticle = false;
    content.question = q;
    const image::ImageRGBA8 image = drawn(content);
    const std::vector<int> fill{64, 69, 84};
    for (int i = 0; i < 7; ++i) EXPECT_EQ(fillAt(image, 70 + i * 27 + 16, 92), fill) << "box " << i << " is lit";
    // Under the row (y 90..108): the labels' line, then the hint's, apart.
    const auto rows = textRowsIn(image, 0, 110, kW, kH);
    ASSERT_GE(rows.size(), 2u) << "labels and a hint under the boxes";
    // The bright ink of a 9 px DejaVu line with ascenders and descenders ("strongly") spans 6
    // rows or more; the labels at 0.3 of the 15 px font (4.5 px) spanned 4 at most.
    EXPECT_GE(rows[0].second, 6) << "end labels " << rows[0].second << " px tall";
    EXPECT_GE(rows[1].second, 6) << "hint " << rows[1].second << " px tall";
    // The min label starts at the first box's left edge, the max label ends at the last box's
    // right edge; nothing of them outside the row's span, none left off the frame.
    EXPECT_GT(brightIn(image, 70, rows[0].first, 110, rows[0].first + rows[0].second), 10);
    EXPECT_GT(brightIn(image, 210, rows[0].first, 250, rows[0].first + rows[0].second), 10);
    EXPECT_EQ(brightIn(image, 0, rows[0].first, 68, rows[0].first + rows[0].second), 0);
    EXPECT_EQ(brightIn(image, 252, rows[0].first, kW, rows[0].first + rows[0].second), 0);
}

// A line longer than the frame is wide (the start screen's, at 320 x 180) wraps onto a second
// line at the size a short one has, rather than shrinking to a few pixels on one; a prompt too.
TEST(Hud, ALongLineWrapsToTheFrameRatherThanShrinking) {
    renderer::HudContent content;
    content.backdrop = true;
    content.reticle = false;
    content.status =
        "Participant P01, protocol shooter-lab, resumed after its last completed trial or match. Press Enter to "
        "start, S to hear the feedback sounds, Esc to leave.";
    renderer::HudQuestion q;
    q.prompt = "How much did the delay between your hand and the view bother you during this block?";
    q.boxes = {{40.0f, 140.0f, 240.0f, 24.0f}};
    q.kind = renderer::HudQuestion::Kind::Text;
    content.question = q;
    const image::ImageRGBA8 image = drawn(content);
    const auto status = textRowsIn(image, 0, 0, kW, 40);
    ASSERT_GE(status.size(), 2u) << "the start line on one line";
    for (const auto& [first, height] : status) EXPECT_GE(height, 6) << "a line at row " << first;
    const auto prompt = textRowsIn(image, 0, 40, kW, 136);
    ASSERT_GE(prompt.size(), 2u) << "the prompt on one line";
    for (const auto& [first, height] : prompt) EXPECT_GE(height, 6) << "a prompt line at row " << first;
}

TEST(Hud, MissingFontIsNamed) {
    testing::glContext();
    try {
        renderer::HudRenderer hud(testing::sourceDataPaths(), "/nowhere/font.ttf");
        FAIL() << "no error";
    } catch (const renderer::AssetError& e) {
        EXPECT_NE(std::string(e.what()).find("/nowhere/font.ttf"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace warplab
