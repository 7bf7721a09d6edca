#include "gl/gl_test_support.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>

namespace warplab::testing {

renderer::GlContext& glContext() {
    static std::unique_ptr<renderer::GlContext> context = [] {
        renderer::ContextOptions options;
        const char* which = std::getenv("WARPLAB_TEST_GL");
        options.backend = renderer::parseBackend(which && *which ? which : "osmesa");
        options.visible = false;
        options.width = 320;
        options.height = 180;
        return renderer::createContext(options);
    }();
    return *context;
}

renderer::DataPaths sourceDataPaths() {
    const std::string root = WARPLAB_SOURCE_DIR;
    return {root + "/shaders", root + "/assets", root + "/analysis"};
}

namespace {
renderer::ConventionalRenderer& conventional() {
    glContext();
    static std::unique_ptr<renderer::ConventionalRenderer> renderer =
        std::make_unique<renderer::ConventionalRenderer>(sourceDataPaths());
    return *renderer;
}
}  // namespace

renderer::GBufferImages renderFrame(const scene::FrameDescription& frame, int width, int height) {
    auto& renderer = conventional();
    renderer::GBuffer gbuffer(width, height);
    renderer.render(frame, gbuffer);
    return renderer::readBack(gbuffer);
}

RenderedSource renderSource(const scene::FrameDescription& frame, int width, int height,
                            const scene::FrameDescription* flowTo, renderer::GuardBand band) {
    auto& renderer = conventional();  // makes the context first
    RenderedSource source;
    source.frame = std::make_unique<renderer::SourceFrame>(width, height, band);
    renderer::renderSource(renderer, frame, *source.frame, flowTo);
    source.images = renderer::readBack(source.frame->gbuffer);
    return source;
}

renderer::DisplayImages produceFrame(const std::string& method, const renderer::UpconversionInput& input, int width,
                                     int height) {
    glContext();
    static std::map<std::string, std::unique_ptr<renderer::UpconversionMethod>> methods;
    auto& m = methods[method];
    if (!m) m = renderer::makeMethod(method, sourceDataPaths());
    renderer::DisplayFrame display(width, height);
    m->produce(input, display);
    return renderer::readBack(display);
}

renderer::DisplayImages produceFrom(const std::string& method, const RenderedSource& source,
                                    const scene::CameraState& camera, double displayTime, int width, int height) {
    renderer::UpconversionInput input;
    input.displayTime = displayTime;
    input.camera = camera;
    input.previous = source.frame.get();
    return produceFrame(method, input, width, height);
}

physics::TargetScene shooterScene(int width, int height, std::uint64_t seed, double speed) {
    physics::TargetSceneConfig config;
    config.aspect = static_cast<double>(width) / height;
    config.seed = seed;
    config.targetSpeed = speed;
    return physics::TargetScene(config);
}

int blackWhereTruthIsNot(const image::ImageRGBA8& shown, const image::ImageRGBA8& truth) {
    int black = 0;
    for (int y = 0; y < shown.height; ++y)
        for (int x = 0; x < shown.width; ++x) {
            const std::uint8_t* s = shown.at(x, y);
            const std::uint8_t* t = truth.at(x, y);
            black += std::max({s[0], s[1], s[2]}) < 8 && std::max({t[0], t[1], t[2]}) >= 32;
        }
    return black;
}

scene::CameraState aimedAt(scene::CameraState camera, const glm::vec3& point) {
    const glm::vec3 d = point - camera.eye;
    camera.yaw = std::atan2(d.x, -d.z);
    camera.pitch = std::asin(d.y / glm::length(d));
    return camera;
}

SpherePass sphereMovingAcross(scene::FrameDescription start, const glm::vec3& velocity, const glm::vec3& aim,
                              int frames) {
    auto& sphere = start.scene.objects.front();
    sphere.position = {-1.0f, 4.0f, -6.0f};
    sphere.velocity = velocity;
    sphere.halfExtents = glm::vec3(0.6f);
    start.camera = aimedAt(start.camera, aim);
    SpherePass pass{start, start, frames / 120.0};
    pass.later.scene.time = start.scene.time + pass.dt;
    pass.later.scene.objects.front().position += velocity * static_cast<float>(pass.dt);
    return pass;
}

std::string testOutputDir() {
    const char* env = std::getenv("WARPLAB_TEST_OUTPUT");
    const std::string dir = env && *env ? env : std::string(WARPLAB_BINARY_DIR) + "/test-output";
    std::filesystem::create_directories(dir);
    return dir;
}

::testing::AssertionResult imagesMatch(const image::ImageRGBA8& expected, const image::ImageRGBA8& actual,
                                       const std::string& label, const ImageThresholds& t) {
    if (expected.width != actual.width || expected.height != actual.height)
        return ::testing::AssertionFailure()
            << label << ": size " << actual.width << "x" << actual.height << " differs from the expected "
            << expected.width << "x" << expected.height;
    const auto diff = image::compareImages(expected, actual, t.pixelThreshold);
    const double share = static_cast<double>(diff.pixelsOverThreshold) / (double(actual.width) * actual.height);
    if (diff.meanChannelDiff <= t.mean && share <= t.maxShareOver) return ::testing::AssertionSuccess();
    const std::string base = testOutputDir() + "/" + label;
    image::writePng(base + ".actual.png", actual);
    image::writePng(base + ".expected.png", expected);
    image::writePng(base + ".diff.png", diff.diffImage);
    return ::testing::AssertionFailure() << label << ": mean channel difference " << diff.meanChannelDiff << " (limit "
                                         << t.mean << "), " << diff.pixelsOverThreshold << " pixels over "
                                         << t.pixelThreshold << " = " << share * 100.0 << "% (limit "
                                         << t.maxShareOver * 100.0 << "%), max " << diff.maxChannelDiff << "; wrote "
                                         << base << ".{actual,expected,diff}.png";
}

::testing::AssertionResult matchesReference(const std::string& name, const image::ImageRGBA8& actual,
                                            const ImageThresholds& thresholds) {
    const std::string path = std::string(WARPLAB_SOURCE_DIR) + "/tests/references/" + name + ".png";
    const char* approve = std::getenv("WARPLAB_APPROVE");
    if (approve != nullptr && std::string(approve) == "1") {
        image::writePng(path, actual);
        return ::testing::AssertionSuccess() << "approved " << path;
    }
    if (!std::filesystem::exists(path)) {
        image::writePng(testOutputDir() + "/" + name + ".actual.png", actual);
        return ::testing::AssertionFailure()
            << "no reference image " << path << " (run scripts/approve-references.sh after checking " << testOutputDir()
            << "/" << name << ".actual.png)";
    }
    return imagesMatch(image::readPng(path), actual, name, thresholds);
}

}  // namespace warplab::testing
