// A condition's frame_times in a protocol: the trace file beside the protocol read, hashed and
// kept inline in the copy a session stores, so the copy reads back without the file; and every
// bad trace refused in one sentence naming the file, line or JSON path.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "shooter/shooter_protocol.h"

namespace warplab::protocol {
namespace {

using Json = nlohmann::ordered_json;
namespace fs = std::filesystem;

class ProtocolTraces : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("warplab-traces-" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_ / "traces");
        write("traces/game.csv", "16\n8\n32\n24\n");  // 20 ms mean: 50 frames a second
    }
    void TearDown() override { fs::remove_all(dir_); }

    void write(const std::string& name, const std::string& text) const { std::ofstream(dir_ / name) << text; }
    std::string protocolPath() const { return (dir_ / "p.json").string(); }

    Json protocol(const Json& frameTimes) const {
        Json p = Json::parse(R"({
          "format_version": 8, "name": "traced", "game": "shooter",
          "display": {"refresh_hz": 144},
          "conditions": {"game": {}},
          "acclimation": {"mode": "conv60"},
          "training": {"high_mode": "conv60", "low_mode": "game"},
          "test": {"conditions": ["conv60", "game"]}
        })");
        p["conditions"]["game"]["frame_times"] = frameTimes;
        return p;
    }
    ShooterProtocol load(const Json& document) const {
        write("p.json", document.dump(2));
        return loadShooterProtocol(protocolPath());
    }
    std::string errorOf(const Json& document) const {
        try {
            load(document);
        } catch (const ProtocolError& e) {
            const std::string message = e.what();
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
            return message;
        }
        return "";
    }

    fs::path dir_;
};

TEST_F(ProtocolTraces, ATraceBesideTheProtocolIsReadHashedAndKeptInTheCopy) {
    const ShooterProtocol p = load(protocol({{"file", "traces/game.csv"}}));
    const condition::Condition& c = p.conditionTable.at("game");
    ASSERT_TRUE(c.frameTimes);
    EXPECT_EQ(c.frameTimes->recordedMs, (std::vector<double>{16, 8, 32, 24}));
    EXPECT_EQ(c.frameTimes->format, "list");
    EXPECT_DOUBLE_EQ(c.renderHz, 50.0);
    // As `printf '16\n8\n32\n24\n' | sha256sum` prints it.
    EXPECT_EQ(c.frameTimes->sha256, "2349382ad81efd1ff1fe0ba09142134382fd144e87bd1760aaabac88ba315143");

    // The stored copy reads back to the same condition with the file gone.
    const std::string copy = toJson(p);
    fs::remove(dir_ / "traces/game.csv");
    const ShooterProtocol again = parseShooterProtocol(copy, "session copy");
    EXPECT_TRUE(again.conditionTable == p.conditionTable);
    EXPECT_EQ(toJson(again), copy);
    const Json stored = Json::parse(copy)["conditions"]["game"];
    EXPECT_FALSE(stored.contains("render_hz"));
    EXPECT_EQ(stored["frame_times"]["file"], "traces/game.csv");
    EXPECT_EQ(stored["frame_times"]["sha256"], c.frameTimes->sha256);
}

TEST_F(ProtocolTraces, AStatedHashPinsTheRecording) {
    const std::string hash = load(protocol({{"file", "traces/game.csv"}})).conditionTable.at("game").frameTimes->sha256;
    EXPECT_EQ(errorOf(protocol({{"file", "traces/game.csv"}, {"sha256", hash}})), "");
    write("traces/game.csv", "16\n8\n32\n25\n");
    EXPECT_EQ(errorOf(protocol({{"file", "traces/game.csv"}, {"sha256", hash}})),
              "protocol '" + protocolPath() + "': conditions.game.frame_times.sha256 is " + hash +
                  ", but the file 'traces/game.csv' has SHA-256 " +
                  load(protocol({{"file", "traces/game.csv"}})).conditionTable.at("game").frameTimes->sha256 +
                  ": the trace has changed since the protocol named it");
}

TEST_F(ProtocolTraces, OffsetAndMeanRateAreKept) {
    const ShooterProtocol p =
        load(protocol({{"file", "traces/game.csv"}, {"offset_s", 0.03}, {"mean_hz", 100}, {"format", "list"}}));
    const condition::Condition& c = p.conditionTable.at("game");
    EXPECT_DOUBLE_EQ(c.renderHz, 100.0);
    EXPECT_EQ(c.frameTimes->offsetS, 0.03);
    EXPECT_TRUE(parseShooterProtocol(toJson(p), "copy").conditionTable == p.conditionTable);
}

TEST_F(ProtocolTraces, BadTracesNameTheFileLineOrPath) {
    const std::string at = "protocol '" + protocolPath() + "': conditions.game.";
    write("traces/zero.csv", "16\n0\n");
    write("traces/empty.csv", "");
    write("traces/odd.csv", "when,what\n1,2\n");
    write("traces/fast.csv", "2\n2\n");
    write("traces/pm.csv", "Application,ProcessID,SwapChainAddress,MsBetweenDisplayChange\na.exe,1,0x1,16\n");
    struct Case {
        Json frameTimes;
        std::string expected;
    };
    const std::vector<Case> cases = {
        {{{"file", "traces/none.csv"}}, "frame_times.file 'traces/none.csv' no such file"},
        {{{"file", "traces/zero.csv"}},
         "frame_times.file 'traces/zero.csv' line 2 the frame time is 0 ms; a frame time must be above 0 and at "
         "most 10000 ms"},
        {{{"file", "traces/empty.csv"}},
         "frame_times.file 'traces/empty.csv' is empty: a trace needs at least one frame time"},
        {{{"file", "traces/odd.csv"}}, "frame_times.file 'traces/odd.csv' is not a frame-time trace warplab reads"},
        {{{"file", "traces/pm.csv"}, {"format", "presentmon"}},
         "frame_times.file 'traces/pm.csv' line 1 is not a PresentMon header: it has no msBetweenPresents, "
         "MsBetweenPresents or FrameTime column"},
        {{{"file", "traces/fast.csv"}},
         "frame_times plays at 500 frames a second, above the refresh (144 Hz): a display shows at most one new "
         "render per refresh; give frame_times.mean_hz up to 144 Hz to play it slower"},
        {{{"file", "traces/game.csv"}, {"format", "capframex"}},
         "frame_times.format must be \"mangohud\", \"presentmon\" or \"list\", got string \"capframex\""},
        {{{"file", "traces/game.csv"}, {"mean_hz", -3}},
         "frame_times.mean_hz must be a number greater than 0 and at most 1000, got -3"},
        {{{"ms", {16.7, 0}}}, "frame_times.ms[1] must be a number greater than 0 and at most 10000, got 0"},
        {{{"ms", {16.7, std::string("NaN")}}}, "frame_times.ms[1] must be a number"},
        {Json::object(), "frame_times needs file: the trace file to play"},
        {{{"file", "traces/game.csv"}, {"loop", true}},
         "frame_times.loop is not a known field (conditions.game.frame_times may have file, format, sha256, "
         "offset_s, mean_hz, ms)"},
    };
    for (const Case& c : cases) {
        const std::string message = errorOf(protocol(c.frameTimes));
        EXPECT_EQ(message.rfind(at + c.expected, 0), 0u) << message << "\nexpected: " << at + c.expected;
    }
    Json both = protocol({{"file", "traces/game.csv"}});
    both["conditions"]["game"]["render_hz"] = 60;
    EXPECT_EQ(errorOf(both),
              at +
                  "render_hz is given by frame_times (the trace's mean rate, or "
                  "frame_times.mean_hz); leave render_hz out");
    // Nothing but the protocol was read: a refusal writes nothing.
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 2);
}

}  // namespace
}  // namespace warplab::protocol
