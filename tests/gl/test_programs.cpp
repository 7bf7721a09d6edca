// Shader loading: errors name the file and the line, whatever the driver's own format.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "gl/gl_test_support.h"
#include "gl/check.h"
#include "gl/program.h"

namespace warplab {
namespace {

std::string scratchShaderDir(const std::string& name) {
    const std::string dir = testing::testOutputDir() + "/" + name;
    std::filesystem::create_directories(dir);
    return dir;
}

void writeFile(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

std::string errorOf(const gl::ProgramDesc& desc) {
    try {
        gl::buildProgram(desc);
    } catch (const gl::GlError& e) {
        return e.what();
    }
    return "";
}

TEST(ShaderProgram, CompileErrorNamesFileAndLine) {
    testing::glContext();
    const std::string dir = scratchShaderDir("broken-shader");
    writeFile(dir + "/ok.vert", "#version 410 core\nvoid main() { gl_Position = vec4(0.0); }\n");
    // The error is on line 5 of the file; the injected defines must not shift it.
    writeFile(dir + "/bad.frag",
              "#version 410 core\n// comment\nout vec4 colour;\nvoid main() {\n    colour = undefinedThing;\n}\n");
    const std::string message =
        errorOf({dir, {{GL_VERTEX_SHADER, "ok.vert"}, {GL_FRAGMENT_SHADER, "bad.frag"}}, {"A 1", "B 2", "C 3"}});
    EXPECT_NE(message.find(dir + "/bad.frag:5"), std::string::npos) << message;
    EXPECT_NE(message.find("fragment shader"), std::string::npos) << message;
}

TEST(ShaderProgram, MissingFileIsNamed) {
    testing::glContext();
    const std::string dir = scratchShaderDir("missing-shader");
    const std::string message = errorOf({dir, {{GL_VERTEX_SHADER, "nowhere.vert"}}, {}});
    EXPECT_NE(message.find("cannot read shader file '" + dir + "/nowhere.vert'"), std::string::npos) << message;
}

TEST(ShaderProgram, LinkErrorIsReported) {
    testing::glContext();
    const std::string dir = scratchShaderDir("link-error");
    writeFile(dir + "/a.vert", "#version 410 core\nvoid main() { gl_Position = vec4(0.0); }\n");
    // Compiles on its own; only linking finds that the stage has no main().
    writeFile(dir + "/b.frag", "#version 410 core\nout vec4 c;\nvoid helper() { c = vec4(1.0); }\n");
    const std::string message = errorOf({dir, {{GL_VERTEX_SHADER, "a.vert"}, {GL_FRAGMENT_SHADER, "b.frag"}}, {}});
    EXPECT_NE(message.find("failed to link"), std::string::npos) << message;
}

TEST(GlObjects, MoveTransfersOwnershipAndEmptyNeedsNoContext) {
    gl::Buffer empty;  // no GL call: safe before any context exists
    EXPECT_FALSE(empty);
    testing::glContext();
    gl::Buffer a = gl::Buffer::create();
    const GLuint id = a.id();
    ASSERT_NE(id, 0u);
    gl::Buffer b = std::move(a);
    EXPECT_EQ(b.id(), id);
    EXPECT_EQ(a.id(), 0u);  // NOLINT(bugprone-use-after-move): the moved-from state is the point
    b.reset();
    EXPECT_FALSE(b);
    gl::checkErrors("deleting a buffer");
}

}  // namespace
}  // namespace warplab
