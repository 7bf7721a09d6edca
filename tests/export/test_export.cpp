// `warplab export`: CSV cells (quoting, formulas, UTF-8, numbers that read back exactly), and
// whole results folders made of real headless sessions, whose CSVs are checked against counts
// taken straight from the stored events -- not through the games' Study::results that export
// uses. Also: incomplete, running, flagged, duplicate, damaged and version-1 sessions, and
// that export changes nothing in the results folder.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "table/csv.h"
#include "game/registry.h"
#include "click/click_protocol.h"
#include "shooter/shooter_protocol.h"
#include "export/export.h"
#include "plan/study_plan.h"
#include "condition/schedule.h"
#include "runner/session_runner.h"
#include "session/session_store.h"
#include "export_test_support.h"
#include "export/documented_columns.h"

namespace warplab::app {
namespace {

using namespace exporttest;

// A session of `source` as another player played it: the same record under a new session id, so
// that it is a session of its own rather than a copy.
std::string replayedAs(const std::string& source, const std::string& dir, const std::string& participant,
                       const std::string& player) {
    session::SessionData data = session::readSession(source);
    data.header.participant = participant;
    data.header.player = player;
    data.header.sessionId = data.header.sessionId.substr(0, data.header.sessionId.size() - 1) +
        (data.header.sessionId.back() == '0' ? "1" : "0");
    session::SessionWriter w = session::SessionWriter::create(dir, data.header);
    for (const auto& r : data.inputs) w.addInput(r);
    for (const auto& r : data.frames) w.addFrame(r);
    for (const auto& e : data.events) w.addEvent(e);
    w.finish();
    return w.path();
}

// ---- the expected numbers, straight from the stored events ----

struct Counts {
    int shots = 0, hits = 0, timeouts = 0;
};
using Key = std::tuple<std::string, std::string, std::string>;  // participant, game, condition

// Scored-phase shots and clicks per participant x game x condition. The shooter's scored phase is
// "test"; a click counts when its match event says the round was scored. The outcome that
// counts is the one the protocol's "scoring" names (world or displayed).
void countScored(const session::SessionData& data, std::map<Key, Counts>& into) {
    const auto protocol = nlohmann::json::parse(data.header.protocolJson);
    const std::string gameName = protocol.value("game", "shooter");
    const std::string scoring = gameName == "shooter" ? protocol.at("test").at("scoring").get<std::string>()
                                                      : protocol.at("matches").at("scoring").get<std::string>();
    std::map<int, bool> scoredMatch;
    for (const auto& e : data.events)
        if (e.type == "match") scoredMatch[e.trial] = nlohmann::json::parse(e.detailJson).at("scored").get<bool>();
    for (const auto& e : data.events) {
        const bool shooterTrial = (e.type == "shot" || e.type == "timeout") && e.phase == "test";
        const bool scoredClick = e.type == "click" && scoredMatch[e.trial];
        if (!shooterTrial && !scoredClick) continue;
        const std::string outcome = scoring == "world" ? e.worldOutcome : e.displayedOutcome;
        Counts& c = into[{data.header.participant, gameName, e.condition}];
        ++c.shots;
        c.hits += outcome == "hit" || outcome == "green";
        c.timeouts += outcome == "timeout";
    }
}

// ---- cells ----

TEST(ExportCsv, TextThatASpreadsheetWouldRunIsDefused) {
    EXPECT_EQ(table::csvText("=1+2"), "'=1+2");
    EXPECT_EQ(table::csvText("+41"), "'+41");
    EXPECT_EQ(table::csvText("-5"), "'-5");
    EXPECT_EQ(table::csvText("@SUM(A1)"), "'@SUM(A1)");
    EXPECT_EQ(table::csvText("\tx"), "'\tx");
    EXPECT_EQ(table::csvText("P-01"), "P-01");  // only the first character matters
    EXPECT_EQ(table::csvText("=HYPERLINK(\"x\",\"y\")"), "\"'=HYPERLINK(\"\"x\"\",\"\"y\"\")\"");
}

// One-to-one: two ids that differ are written differently ("=1" and "'=1" were both '=1, and the
// analysis then took two participants for one), and one leading ' dropped gives the original.
TEST(ExportCsv, TheEscapeIsOneToOne) {
    EXPECT_EQ(table::csvText("=1"), "'=1");
    EXPECT_EQ(table::csvText("'=1"), "''=1");
    EXPECT_EQ(table::csvText("'quoted"), "''quoted");
    for (const std::string id : {"=1", "'=1", "''=1", "'x", "x", "-3", "'-3", "P01"}) {
        const std::string cell = table::csvText(id);
        const std::string back = cell.rfind('\'', 0) == 0 ? cell.substr(1) : cell;
        EXPECT_EQ(back, id) << cell;
    }
}

TEST(ExportCsv, TextIsQuotedOnlyWhereRfc4180NeedsIt) {
    EXPECT_EQ(table::csvText("plain text"), "plain text");
    EXPECT_EQ(table::csvText("a,b"), "\"a,b\"");
    EXPECT_EQ(table::csvText("say \"hi\""), "\"say \"\"hi\"\"\"");
    EXPECT_EQ(table::csvText("two\nlines"), "\"two\nlines\"");
    EXPECT_EQ(table::csvText(""), "");
}

TEST(ExportCsv, InvalidUtf8BecomesTheReplacementCharacterAndValidUtf8Stays) {
    EXPECT_EQ(table::csvText("caf\xC3\xA9"), "caf\xC3\xA9");
    EXPECT_EQ(table::csvText("\xF0\x9F\x98\x80"), "\xF0\x9F\x98\x80");  // U+1F600
    EXPECT_EQ(table::csvText("a\xFFz"), "a\xEF\xBF\xBDz");  // stray byte
    EXPECT_EQ(table::csvText("\xC3"), "\xEF\xBF\xBD");  // cut sequence
    EXPECT_EQ(table::csvText("\xC0\xAF"), "\xEF\xBF\xBD\xEF\xBF\xBD");  // overlong '/'
    EXPECT_EQ(table::csvText("\xED\xA0\x80"), "\xEF\xBF\xBD\xEF\xBF\xBD\xEF\xBF\xBD");  // a surrogate
}

TEST(ExportCsv, NumbersReadBackBitForBit) {
    std::mt19937_64 random(7);
    std::vector<double> values{0.1, 1.0 / 3.0, -0.0, 1e-300, 4.9e-324, 1.7976931348623157e308, 2.0 / 3.0, 25.0};
    for (int i = 0; i < 2000; ++i) {
        double d;
        const std::uint64_t bits = random();
        std::memcpy(&d, &bits, sizeof d);
        if (std::isfinite(d)) values.push_back(d);
    }
    for (const double v : values) {
        const std::string text = table::csvNumber(v);
        EXPECT_EQ(text.find(','), std::string::npos) << text;
        const double back = std::strtod(text.c_str(), nullptr);
        EXPECT_EQ(std::memcmp(&back, &v, sizeof v), 0) << text;
    }
    EXPECT_EQ(table::csvNumber(0.1), "0.1");  // shortest, not 0.10000000000000001
    EXPECT_EQ(table::csvNumber(std::nan("")), "");
    EXPECT_EQ(table::csvNumber(HUGE_VAL), "Inf");
    EXPECT_EQ(table::csvNumber(-HUGE_VAL), "-Inf");
}

TEST(ExportCsv, ARowWithTheWrongNumberOfCellsIsRefusedAndNoFileIsLeft) {
    const std::string dir = scratch("wrong-cells");
    {
        table::CsvFile f(dir + "/t.csv", {"a", "b"});
        f.text("x");
        EXPECT_THROW(f.endRow(), std::logic_error);
    }
    EXPECT_FALSE(fs::exists(dir + "/t.csv"));
    EXPECT_FALSE(fs::exists(dir + "/t.csv.partial"));
}

// ---- whole folders ----

// Two participants' shooter sessions and a click session in a sub-folder: every CSV's numbers
// against counts taken straight from the stored events.
TEST(Export, AFolderOfRealSessionsGivesTheCountsTheEventsHold) {
    const std::string results = scratch("real/results"), out = scratch("real/out");
    fs::create_directories(results + "/day2");
    const std::vector<std::string> files{headless("shooter-quick.json", "P01", results, 1),
                                         headless("shooter-quick.json", "P02", results, 2),
                                         headless("click-quick.json", "P01", results + "/day2", 3)};
    std::map<Key, Counts> expected;
    int scoredMatches = 0, ratingEvents = 0;
    for (const auto& f : files) {
        const auto data = session::readSession(f);
        countScored(data, expected);
        for (const auto& e : data.events) {
            if (e.type == "match" && nlohmann::json::parse(e.detailJson).at("scored").get<bool>()) ++scoredMatches;
            if (e.type == "rating" && e.phase == "scored") ++ratingEvents;
        }
    }
    ASSERT_GE(expected.size(), 6u);

    const exporter::ExportSummary summary = exportQuietly(results, out);
    ASSERT_EQ(summary.sessions.size(), 3u);
    for (const auto& s : summary.sessions) EXPECT_TRUE(s.included) << s.file << ": " << s.status << " " << s.why;
    EXPECT_EQ(summary.sessions[0].file, "P01_" + fs::path(files[0]).filename().string().substr(4));
    EXPECT_EQ(summary.sessions[2].file.rfind("day2/", 0), 0u) << summary.sessions[2].file;

    // hitrates.csv: exactly the expected rows, rates exactly hits/shots.
    EXPECT_EQ(headerOf(out + "/hitrates.csv"),
              (std::vector<std::string>{"participant", "game", "condition", "shots", "hits", "timeouts", "hit_rate",
                                        "player_kind"}));
    const auto hitrates = readCsv(out + "/hitrates.csv");
    ASSERT_EQ(hitrates.size(), expected.size());
    int clickRows = 0;
    for (const auto& row : hitrates) {
        const Key key{row.at("participant"), row.at("game"), row.at("condition")};
        ASSERT_EQ(expected.count(key), 1u) << row.at("participant") << " " << row.at("condition");
        const Counts& c = expected[key];
        EXPECT_EQ(std::stoi(row.at("shots")), c.shots);
        EXPECT_EQ(std::stoi(row.at("hits")), c.hits);
        EXPECT_EQ(std::strtod(row.at("hit_rate").c_str(), nullptr), static_cast<double>(c.hits) / c.shots);
        if (row.at("game") == "click") {
            ++clickRows;
            EXPECT_EQ(row.at("timeouts"), "");  // the click game has none to count
        } else {
            EXPECT_EQ(std::stoi(row.at("timeouts")), c.timeouts);
        }
    }
    EXPECT_GE(clickRows, 3);

    // shots.csv: one row per scored shot or click, none from other phases.
    int expectedShots = 0;
    for (const auto& [key, c] : expected) expectedShots += c.shots;
    const auto shots = readCsv(out + "/shots.csv");
    EXPECT_EQ(static_cast<int>(shots.size()), expectedShots);
    for (const auto& s : shots) {
        EXPECT_EQ(s.at("scored_phase"), "true");
        EXPECT_EQ(s.at("hit") == "true", s.at("outcome") == "hit" || s.at("outcome") == "green");
        if (s.at("game") == "shooter") {
            EXPECT_EQ(s.at("phase"), "test");
            EXPECT_FALSE(s.at("aim_time_s").empty());
            EXPECT_NEAR(std::stod(s.at("time_s")) - std::stod(s.at("spawn_time_s")), std::stod(s.at("aim_time_s")),
                        1e-9);
            EXPECT_EQ(s.at("error_px"), "");
        } else {
            EXPECT_EQ(s.at("aim_time_s"), "");
            EXPECT_EQ(s.at("angular_error_deg"), "");
        }
    }

    // matches.csv and ratings.csv: the scored round's matches, four ratings each.
    const auto matches = readCsv(out + "/matches.csv");
    EXPECT_EQ(static_cast<int>(matches.size()), scoredMatches);
    // The ratings last but for the columns added after them (export.cpp: matchTrailingColumns).
    const auto matchHeader = headerOf(out + "/matches.csv");
    EXPECT_EQ(std::vector<std::string>(matchHeader.end() - 4, matchHeader.end()),
              (std::vector<std::string>{"rating_4", "player_kind", "condition_position", "frame_time_p95_ms"}));
    for (const auto& m : matches) {
        EXPECT_EQ(std::stoi(m.at("clicks")),
                  std::stoi(m.at("green_hits")) + std::stoi(m.at("red_hits")) + std::stoi(m.at("misses")));
        for (int k = 1; k <= 4; ++k) EXPECT_FALSE(m.at("rating_" + std::to_string(k)).empty());
    }
    EXPECT_EQ(static_cast<int>(readCsv(out + "/ratings.csv").size()), ratingEvents);

    // games.csv: each game once, in the registry's order, with the words for its hit rate.
    EXPECT_EQ(slurp(out + "/games.csv"),
              "game,hits_are,shots_are,tables\nshooter,hits,shots,\nclick,green hits,clicks,matches.csv;ratings.csv\n");

    // --all-phases adds acclimation, training and the practice round to shots.csv, not to hit rates.
    const std::string all = scratch("real/all");
    exporter::ExportOptions options;
    options.allPhases = true;
    exportQuietly(results, all, options);
    EXPECT_GT(readCsv(all + "/shots.csv").size(), shots.size());
    EXPECT_GT(readCsv(all + "/matches.csv").size(), matches.size());
    EXPECT_EQ(slurp(all + "/hitrates.csv"), slurp(out + "/hitrates.csv"));
}

// conditions.csv lists every condition the sessions' protocols run, once per game and refresh,
// each cell what the condition and its schedule say, so an analysis reading it needs no list of
// conditions of its own.
TEST(Export, ConditionsCsvListsWhatTheSessionsRan) {
    const std::string results = scratch("conditions/results"), out = scratch("conditions/out");
    headless("shooter-quick.json", "P01", results, 1);
    exportQuietly(results, out);
    const auto rows = readCsv(out + "/conditions.csv");
    const auto study = game::loadStudy(std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-quick.json");
    std::vector<std::string> used;
    for (const auto& m : study->conditionNames())
        if (std::find(used.begin(), used.end(), m) == used.end()) used.push_back(m);
    ASSERT_EQ(rows.size(), used.size());
    for (std::size_t i = 0; i < used.size(); ++i) {
        const condition::ConditionSummary c = condition::summarize(study->conditions().at(used[i]), study->refreshHz());
        const Row& row = rows[i];
        SCOPED_TRACE(used[i]);
        EXPECT_EQ(row.at("condition"), used[i]);
        EXPECT_EQ(row.at("description"), c.condition.description);
        EXPECT_EQ(std::stod(row.at("render_hz")), c.condition.renderHz);
        EXPECT_EQ(std::stoll(row.at("lag_frames")), c.lagFrames);
        EXPECT_EQ(row.at("fill"), c.condition.fill);
        EXPECT_EQ(row.at("late_warp"), condition::lateWarpName(c.condition.lateWarp));
        EXPECT_EQ(std::stod(row.at("view_latency_min_ms")), c.viewS.min * 1000.0);
        EXPECT_EQ(std::stod(row.at("view_latency_max_ms")), c.viewS.max * 1000.0);
        EXPECT_EQ(std::stod(row.at("scene_latency_min_ms")), c.sceneS.min * 1000.0);
        EXPECT_EQ(std::stod(row.at("scene_latency_max_ms")), c.sceneS.max * 1000.0);
        EXPECT_EQ(std::stod(row.at("refresh_hz")), 120.0);
        EXPECT_EQ(row.at("game"), "shooter");
    }
    // Spelled out once, independently of the condition's own accessors.
    const auto row = [&](const std::string& id) {
        const auto it = std::find_if(rows.begin(), rows.end(), [&](const Row& r) { return r.at("condition") == id; });
        EXPECT_NE(it, rows.end()) << id;
        return it == rows.end() ? Row{} : *it;
    };
    const Row warp = row("warp15to120");
    EXPECT_EQ(warp.at("render_hz"), "15");
    EXPECT_EQ(warp.at("fill"), "warp-sparse8");
    EXPECT_EQ(warp.at("fill_hz"), "120");
    EXPECT_EQ(warp.at("late_warp"), "none");
    EXPECT_EQ(warp.at("view_latency_min_ms"), "0");
    EXPECT_NEAR(std::stod(warp.at("view_latency_max_ms")), 1000.0 / 120, 1e-9);
    EXPECT_NEAR(std::stod(warp.at("scene_latency_max_ms")), 8000.0 / 120, 1e-9);
    const Row conv15 = row("conv15");
    EXPECT_EQ(conv15.at("fill"), "hold");
    EXPECT_EQ(conv15.at("fill_hz"), "");
    EXPECT_EQ(conv15.at("lag_frames"), "0");
    // Pacing: 15 renders a second held, a step waits half a render period in the median.
    EXPECT_EQ(conv15.at("mean_fps"), "15");
    EXPECT_NEAR(std::stod(conv15.at("frame_time_p95_ms")), 1000.0 / 15, 1e-9);
    EXPECT_NEAR(std::stod(conv15.at("low_1pct_fps")), 15, 1e-9);
    EXPECT_EQ(conv15.at("stutters"), "0");
    EXPECT_NEAR(std::stod(conv15.at("view_latency_median_ms")), 1000.0 / 30, 1e-6);
    EXPECT_EQ(warp.at("mean_fps"), "120");  // every warped frame is a new image
    EXPECT_NEAR(std::stod(warp.at("frame_time_max_ms")), 1000.0 / 120, 1e-9);

    // frametimes.csv: the frame times behind those numbers, 10 s of each condition.
    std::map<std::string, std::vector<double>> times;
    for (const Row& r : readCsv(out + "/frametimes.csv")) {
        EXPECT_EQ(r.at("game"), "shooter");
        EXPECT_GT(std::stod(r.at("time_s")), 0.0);
        EXPECT_LT(std::stod(r.at("time_s")), 10.0);
        times[r.at("condition")].push_back(std::stod(r.at("frame_time_ms")));
    }
    EXPECT_EQ(times.size(), used.size());
    EXPECT_EQ(times["conv15"].size(), 149u);  // 150 new images, each but the first from the one before
    for (const double t : times["conv15"]) EXPECT_NEAR(t, 1000.0 / 15, 1e-9);
    EXPECT_EQ(times["warp15to120"].size(), 1199u);
}

// Each shot's frame_time_p95_ms: from the session's own frames table, over the trial's last
// second. Headless sessions keep their conditions' steady cadences, so it is the render period
// of a hold and the refresh of a warp; with every other frame of a shot's last second held, twice that.
TEST(Export, EachShotCarriesTheFrameTimeP95OfItsLastSecond) {
    const std::string results = scratch("shot-p95/results"), out = scratch("shot-p95/out");
    const std::string file = headless("shooter-quick.json", "P01", results, 1);
    exportQuietly(results, out);
    const std::map<std::string, double> expected{
        {"conv15", 1000.0 / 15}, {"conv120", 1000.0 / 120}, {"warp15to120", 1000.0 / 120}};
    int checked = 0;
    for (const Row& r : readCsv(out + "/shots.csv")) {
        if (r.at("frame_time_p95_ms").empty()) continue;  // a trial too short for two new images
        EXPECT_NEAR(std::stod(r.at("frame_time_p95_ms")), expected.at(r.at("condition")), 1e-9) << r.at("trial");
        ++checked;
    }
    EXPECT_GE(checked, 10);

    // The same session with every odd frame of conv120's trials held: 16.7 ms, never 8.3.
    session::SessionData data = session::readSession(file);
    fs::remove_all(results);
    fs::create_directories(results);
    session::SessionHeader header = data.header;
    header.startedAt = "";
    session::SessionWriter w = session::SessionWriter::create(results, header);
    for (session::FrameRecord f : data.frames) {
        if (f.condition == "conv120" && f.kind == "rendered" && f.frame % 2 == 1) f.kind = "held";
        w.addFrame(f);
    }
    for (const auto& e : data.events) w.addEvent(e);
    w.finish();
    exportQuietly(results, out);
    int held = 0;
    for (const Row& r : readCsv(out + "/shots.csv")) {
        if (r.at("condition") != "conv120" || r.at("frame_time_p95_ms").empty()) continue;
        EXPECT_NEAR(std::stod(r.at("frame_time_p95_ms")), 2000.0 / 120, 1e-9) << r.at("trial");
        ++held;
    }
    EXPECT_GE(held, 3);
}

// A session's results with a new participant id (and start time), as if run again.
std::string rewrite(const session::SessionData& data, const std::string& dir, const std::string& participant,
                    std::size_t events, bool finish, const std::string& flag = "") {
    session::SessionHeader header = data.header;
    header.participant = participant;
    header.startedAt = "";  // now: another session
    session::SessionWriter w = session::SessionWriter::create(dir, header);
    for (std::size_t i = 0; i < events && i < data.events.size(); ++i) w.addEvent(data.events[i]);
    if (!flag.empty()) w.flag(flag, "12.5 % of frames missed their vsync");
    if (finish)
        w.finish();
    else
        w.commit();
    return w.path();
}

// Every file under dir with its size and a hash of its bytes (but SQLite's shared-memory
// index, which readers may touch).
std::map<std::string, std::string> snapshot(const std::string& dir) {
    std::map<std::string, std::string> files;
    for (const auto& e : fs::recursive_directory_iterator(dir)) {
        const std::string p = e.path().filename().string();
        if (!e.is_regular_file()) {
            files[p] = "not a regular file";
        } else if (p.size() < 4 || p.compare(p.size() - 4, 4, "-shm") != 0) {
            const std::string bytes = slurp(e.path().string());
            files[p] = std::to_string(bytes.size()) + " bytes, hash " + std::to_string(std::hash<std::string>{}(bytes));
        } else {
            files[p] = "shm";
        }
    }
    return files;
}

TEST(Export, IncompleteFlaggedDuplicateAndDamagedSessionsAreListedAndLeftOutUnlessAskedFor) {
    const std::string results = scratch("mixed/results"), source = scratch("mixed/source");
    const auto data = session::readSession(headless("shooter-quick.json", "OK", source, 4));
    // Cut in the middle of the test phase: some scored trials survive, not all.
    std::vector<std::size_t> testShots;
    for (std::size_t i = 0; i < data.events.size(); ++i)
        if (data.events[i].type == "shot" && data.events[i].phase == "test") testShots.push_back(i);
    ASSERT_GE(testShots.size(), 4u);
    const std::size_t cut = testShots[testShots.size() / 2];
    const std::string complete = rewrite(data, results, "OK", data.events.size(), true);
    const std::string incomplete = rewrite(data, results, "CUT", cut, false);
    const std::string flagged = rewrite(data, results, "FLAG", data.events.size(), true, "missed_frames");
    fs::copy_file(complete, results + "/copy-of-ok.warplab-session");
    { std::ofstream(results + "/garbage.warplab-session") << "this is not a database, just text"; }
    // A copy cut short, listed before the whole one: readable up to the cut, committed data
    // lost, so "damaged" (replay's exit 4), and it must not make the whole copy a duplicate.
    fs::copy_file(complete, results + "/A-cut.warplab-session");
    fs::resize_file(results + "/A-cut.warplab-session", fs::file_size(complete) * 6 / 10);
    { std::ofstream(results + "/.hidden-being-created.warplab-session") << "ignored"; }
    { std::ofstream(results + "/notes.txt") << "ignored"; }
    ASSERT_EQ(::mkfifo((results + "/pipe.warplab-session").c_str(), 0600), 0);  // must not block the export
    // A session still being written: its writer holds the file open with a WAL beside it.
    session::SessionWriter running = [&] {
        session::SessionHeader header = data.header;
        header.participant = "LIVE";
        header.startedAt = "";
        session::SessionWriter w = session::SessionWriter::create(results, header);
        for (std::size_t i = 0; i < cut; ++i) w.addEvent(data.events[i]);
        w.commit();
        return w;
    }();

    const auto before = snapshot(results);
    std::string log;
    const std::string out = scratch("mixed/out");
    const exporter::ExportSummary summary = exportQuietly(results, out, {}, &log);
    EXPECT_EQ(snapshot(results), before) << "export changed the results folder";

    std::map<std::string, std::string> status;
    std::map<std::string, bool> included;
    for (const auto& s : summary.sessions) {
        status[s.file] = s.status;
        included[s.file] = s.included;
    }
    const auto name = [&](const std::string& path) { return fs::path(path).filename().string(); };
    ASSERT_EQ(summary.sessions.size(), 7u) << log;  // no hidden file, no text file, no pipe
    EXPECT_EQ(status["A-cut.warplab-session"], "damaged");
    EXPECT_EQ(status[name(complete)], "ok");
    EXPECT_EQ(status[name(incomplete)], "incomplete");
    EXPECT_EQ(status[name(running.path())], "incomplete");
    EXPECT_EQ(status[name(flagged)], "flagged");
    EXPECT_EQ(status["garbage.warplab-session"], "damaged");
    // Files are read in path order: OK_... before copy-of-ok, so the copy is the duplicate.
    EXPECT_EQ(status["copy-of-ok.warplab-session"], "duplicate");
    EXPECT_TRUE(log.find("garbage.warplab-session") != std::string::npos) << log;
    EXPECT_TRUE(log.find("pipe.warplab-session") != std::string::npos) << log;

    const auto sessions = readCsv(out + "/sessions.csv");
    ASSERT_EQ(sessions.size(), 7u);
    for (const auto& row : sessions) {
        EXPECT_EQ(row.at("included"), included[row.at("file")] ? "true" : "false") << row.at("file");
        EXPECT_EQ(row.at("status"), status[row.at("file")]);
        if (row.at("status") == "flagged") {
            EXPECT_EQ(row.at("flags"), "missed_frames");
        }
        if (row.at("status") == "damaged") {
            EXPECT_FALSE(row.at("note").empty());
        }
    }

    std::map<std::string, int> scoredShots;  // by participant
    for (const auto& s : readCsv(out + "/shots.csv")) ++scoredShots[s.at("participant")];
    std::map<Key, Counts> expected;
    countScored(data, expected);
    int perSession = 0;
    for (const auto& [key, c] : expected) perSession += c.shots;
    ASSERT_GT(perSession, 0);
    EXPECT_EQ(scoredShots.size(), 1u) << "only the complete session (once) by default";
    EXPECT_EQ(scoredShots["OK"], perSession);

    exporter::ExportOptions more;
    more.includeIncomplete = more.includeFlagged = true;
    const std::string outAll = scratch("mixed/out-all");
    exportQuietly(results, outAll, more);
    std::map<std::string, int> allShots;
    for (const auto& s : readCsv(outAll + "/shots.csv")) ++allShots[s.at("participant")];
    EXPECT_EQ(allShots["OK"], perSession) << "a duplicate never counts twice";
    EXPECT_EQ(allShots["FLAG"], perSession);
    EXPECT_GT(allShots["CUT"], 0);
    EXPECT_LT(allShots["CUT"], perSession);
    EXPECT_EQ(allShots.count("LIVE"), 1u);
    EXPECT_EQ(snapshot(results), before);
}

// Two sessions of one participant started in the same millisecond with the same seed and
// protocol -- two rigs, or a runner script started twice -- are two sessions, not a copy:
// their ids differ. A copy of one keeps its id and is the duplicate.
TEST(Export, TwinSessionsAreTwoSessionsAndOnlyACopyIsADuplicate) {
    const std::string results = scratch("twins/results"), source = scratch("twins/source"),
                      other = scratch("twins/other");
    const auto data = session::readSession(headless("shooter-quick.json", "T", source, 4));
    session::SessionHeader header = data.header;
    header.startedAt = "2026-05-06T07:08:09.123Z";
    std::vector<std::string> paths;
    for (const std::string& dir : {results, other}) {
        session::SessionWriter w = session::SessionWriter::create(dir, header);
        for (const auto& e : data.events) w.addEvent(e);
        w.finish();
        paths.push_back(w.path());
    }
    fs::copy_file(paths[1], results + "/twin.warplab-session");
    fs::copy_file(paths[0], results + "/zz-copy.warplab-session");
    const exporter::ExportSummary summary = exportQuietly(results, scratch("twins/out"));
    std::map<std::string, std::string> status;
    for (const auto& s : summary.sessions) status[s.file] = s.status;
    ASSERT_EQ(status.size(), 3u);
    EXPECT_EQ(status[fs::path(paths[0]).filename().string()], "ok");
    EXPECT_EQ(status["twin.warplab-session"], "ok");
    EXPECT_EQ(status["zz-copy.warplab-session"], "duplicate");
}

// A session's header under another participant id, with the events given.
std::string rewriteEvents(const session::SessionData& data, const std::string& dir, const std::string& participant,
                          const std::vector<session::EventRecord>& events) {
    session::SessionHeader header = data.header;
    header.participant = participant;
    header.startedAt = "";
    session::SessionWriter w = session::SessionWriter::create(dir, header);
    for (const auto& e : events) w.addEvent(e);
    w.finish();
    return w.path();
}

bool scoredMatch(const session::EventRecord& e) {
    return e.type == "match" && nlohmann::json::parse(e.detailJson).at("scored").get<bool>();
}

// A participant who played a scored match without clicking still ran its condition: hitrates.csv
// has that participant x condition, with 0 clicks, 0 hits and no rate (an empty cell, NA in R), so
// every participant x condition run appears, and none has a rate of 0/0.
TEST(Export, AConditionPlayedWithoutAClickHasAHitRateRowWithoutARate) {
    const std::string source = scratch("no-clicks/source"), results = scratch("no-clicks/results");
    const auto data = session::readSession(headless("click-quick.json", "Z", source, 8));
    const auto first = std::find_if(data.events.begin(), data.events.end(), scoredMatch);
    ASSERT_NE(first, data.events.end());
    const int trial = first->trial;
    const std::string condition = first->condition;
    std::vector<session::EventRecord> events;
    int dropped = 0;
    std::set<std::string> conditions;
    for (auto e : data.events) {
        if (scoredMatch(e)) conditions.insert(e.condition);
        if (e.type == "click" && e.trial == trial) {
            ++dropped;
            continue;
        }
        if (e.type == "match" && e.trial == trial) {
            auto detail = nlohmann::json::parse(e.detailJson);
            for (const char* count : {"green_hits", "red_hits", "misses", "clicks"}) detail[count] = 0;
            e.detailJson = detail.dump();
        }
        events.push_back(e);
    }
    ASSERT_GT(dropped, 0);
    rewriteEvents(data, results, "Z", events);
    const std::string out = scratch("no-clicks/out");
    exportQuietly(results, out);
    std::map<std::string, Row> byCondition;
    for (const auto& row : readCsv(out + "/hitrates.csv")) byCondition[row.at("condition")] = row;
    EXPECT_EQ(byCondition.size(), conditions.size()) << "one row per mode the scored round ran";
    ASSERT_EQ(byCondition.count(condition), 1u) << condition << " has no row";
    const Row& row = byCondition[condition];
    EXPECT_EQ(row.at("shots"), "0");
    EXPECT_EQ(row.at("hits"), "0");
    EXPECT_EQ(row.at("hit_rate"), "");
    EXPECT_EQ(row.at("timeouts"), "");
}

// A click-game match a session was cut short in never ended: it has no result, so no
// matches.csv row, and its clicks are in neither shots.csv nor hitrates.csv, which both count
// exactly the clicks of the matches matches.csv lists.
TEST(Export, AClickMatchThatNeverEndedLeavesItsClicksOut) {
    const std::string source = scratch("cut-match/source"), results = scratch("cut-match/results");
    const auto data = session::readSession(headless("click-quick.json", "C", source, 9));
    // Cut just before the second scored match ends, after some of its clicks.
    std::vector<std::size_t> ends;
    for (std::size_t i = 0; i < data.events.size(); ++i)
        if (scoredMatch(data.events[i])) ends.push_back(i);
    ASSERT_GE(ends.size(), 2u);
    const std::size_t cut = ends[1];
    const int cutTrial = data.events[cut].trial;
    const auto clicksOfCut = std::count_if(data.events.begin(), data.events.begin() + static_cast<std::ptrdiff_t>(cut),
                                           [&](const auto& e) { return e.type == "click" && e.trial == cutTrial; });
    ASSERT_GT(clicksOfCut, 0);
    rewrite(data, results, "C", cut, false);

    exporter::ExportOptions options;
    options.includeIncomplete = true;
    const std::string out = scratch("cut-match/out");
    exportQuietly(results, out, options);
    std::set<std::string> listed;
    std::map<std::string, int> clicksByCondition;
    for (const auto& m : readCsv(out + "/matches.csv")) {
        listed.insert(m.at("match"));
        clicksByCondition[m.at("condition")] += std::stoi(m.at("clicks"));
    }
    EXPECT_EQ(listed.count(std::to_string(cutTrial)), 0u);
    const auto shots = readCsv(out + "/shots.csv");
    ASSERT_FALSE(shots.empty()) << "the first scored match ended and counts";
    for (const auto& s : shots) EXPECT_EQ(listed.count(s.at("trial")), 1u) << "a click of match " << s.at("trial");
    std::map<std::string, int> hitrateClicks;
    for (const auto& row : readCsv(out + "/hitrates.csv"))
        hitrateClicks[row.at("condition")] = std::stoi(row.at("shots"));
    EXPECT_EQ(hitrateClicks, clicksByCondition);
}

TEST(Export, ParticipantIdsCannotBecomeFormulasOrBreakTheColumns) {
    const std::string results = scratch("ids/results"), source = scratch("ids/source");
    const auto data = session::readSession(headless("shooter-quick.json", "x", source, 5));
    for (const char* id : {"=1+2", "-5", "@cmd", "+A1", "a,b \"c\"", "caf\xC3\xA9", "bad\xFFid"})
        rewrite(data, results, id, data.events.size(), true);
    const std::string out = scratch("ids/out");
    exportQuietly(results, out);
    std::set<std::string> ids;
    for (const auto& row : readCsv(out + "/hitrates.csv")) ids.insert(row.at("participant"));
    EXPECT_EQ(
        ids, (std::set<std::string>{"'=1+2", "'-5", "'@cmd", "'+A1", "a,b \"c\"", "caf\xC3\xA9", "bad\xEF\xBF\xBDid"}));
}

TEST(Export, AVersion1SessionExportsItsScoredTrials) {
    const std::string results = scratch("v1/results");
    const std::string fixture = std::string(WARPLAB_SOURCE_DIR) + "/tests/data/v1-shooter-quick.warplab-session";
    fs::copy_file(fixture, results + "/v1.warplab-session");
    std::map<Key, Counts> expected;
    countScored(session::readSession(fixture), expected);
    ASSERT_FALSE(expected.empty());
    const std::string out = scratch("v1/out");
    exportQuietly(results, out);
    const auto rows = readCsv(out + "/hitrates.csv");
    ASSERT_EQ(rows.size(), expected.size());
    for (const auto& row : rows) {
        const Counts& c = expected[{row.at("participant"), row.at("game"), row.at("condition")}];
        EXPECT_EQ(std::stoi(row.at("shots")), c.shots);
        EXPECT_EQ(std::stoi(row.at("hits")), c.hits);
    }
}

// Click sessions recorded while `blend` stood in for bidirectional reprojection carry
// "stand_in" in their match events. They still replay (the note describes the rendering, not
// what was played), and export says which matches were drawn so.
TEST(Export, SessionsRecordedWithTheBlendStandInStillReplayAndSaySo) {
    const std::string source = scratch("stand-in/source"), results = scratch("stand-in/results");
    const auto data = session::readSession(headless("click-quick.json", "S", source, 6));
    session::SessionWriter w = session::SessionWriter::create(results, data.header);
    for (const auto& r : data.inputs) w.addInput(r);
    for (const auto& r : data.frames) w.addFrame(r);
    int marked = 0;
    for (auto e : data.events) {
        if (e.type == "match" && e.condition == "bireproj15to60") {
            auto detail = nlohmann::json::parse(e.detailJson);
            detail["stand_in"] = "bidirectional reprojection";
            e.detailJson = detail.dump();
            ++marked;
        }
        w.addEvent(e);
    }
    ASSERT_GT(marked, 0);
    w.finish();
    const runner::ReplayResult replay = runner::replaySession(w.path());
    EXPECT_EQ(replay.difference, "");
    EXPECT_EQ(replay.reproduced, replay.outcomes);
    EXPECT_GT(replay.outcomes, 0u);

    const std::string out = scratch("stand-in/out");
    exporter::ExportOptions all;
    all.allPhases = true;
    exportQuietly(results, out, all);
    int standIns = 0;
    for (const auto& m : readCsv(out + "/matches.csv")) {
        EXPECT_EQ(m.at("stand_in").empty(), m.at("condition") != "bireproj15to60") << m.at("condition");
        standIns += !m.at("stand_in").empty();
    }
    EXPECT_EQ(standIns, marked);
}

// ratings.csv carries the scale each answer was given on, from the session's stored protocol,
// so an analysis reads a study's own ratings.min and ratings.max instead of assuming 1 to 7.
TEST(Export, RatingsCarryTheProtocolsScale) {
    const std::string source = scratch("scale/source"), results = scratch("scale/results");
    auto protocol = nlohmann::json::parse(slurp(std::string(WARPLAB_SOURCE_DIR) + "/protocol/click-quick.json"));
    protocol["ratings"]["min"] = 0;
    protocol["ratings"]["max"] = 10;
    const std::string path = source + "/click-0-10.json";
    std::ofstream(path) << protocol.dump(2);
    runner::HeadlessRun run;
    run.protocolPath = path;
    run.participant = "T";
    run.resultsDir = results;
    run.player = "bot:11";
    run.seed = 11;
    std::ostringstream quiet;
    runner::runHeadless(run, quiet);

    const std::string out = scratch("scale/out");
    exportQuietly(results, out);
    const auto header = headerOf(out + "/ratings.csv");
    for (const std::string column : {"scale_min", "scale_max"})
        ASSERT_NE(std::find(header.begin(), header.end(), column), header.end()) << "ratings.csv has no " << column;
    const auto ratings = readCsv(out + "/ratings.csv");
    ASSERT_FALSE(ratings.empty());
    for (const auto& r : ratings) {
        EXPECT_EQ(r.at("scale_min"), "0");
        EXPECT_EQ(r.at("scale_max"), "10");
        const int value = std::stoi(r.at("value"));
        EXPECT_GE(value, 0);
        EXPECT_LE(value, 10);
    }
}

// A protocol file in `dir` from a shipped one, changed by `edit`; its path.
std::string editedProtocol(const std::string& dir, const std::string& shipped,
                           const std::function<void(nlohmann::json&)>& edit) {
    auto protocol = nlohmann::json::parse(slurp(std::string(WARPLAB_SOURCE_DIR) + "/protocol/" + shipped));
    edit(protocol);
    const std::string path = dir + "/" + shipped;
    std::ofstream(path) << protocol.dump(2);
    return path;
}

// answers.csv: every answer after a block, of every kind and both games, as the events hold
// them; the click game's Likert answers are its ratings as well.
TEST(Export, AnswersCsvHoldsEveryAnswerOfEveryKindAndGame) {
    const std::string source = scratch("answers/source"), results = scratch("answers/results");
    const nlohmann::json questions = nlohmann::json::parse(R"([
        {"id": "fun", "kind": "likert", "prompt": "It was fun", "min": 0, "max": 10,
         "min_label": "not at all", "max_label": "very"},
        {"id": "better", "kind": "choice", "prompt": "Which felt better?",
         "options": ["this one", "the one before", "no difference"]},
        {"id": "comment", "kind": "text", "prompt": "Anything else?"}])");
    const std::string click = editedProtocol(source, "click-quick.json", [&](nlohmann::json& p) {
        p["format_version"] = protocol::kClickQuestionsSince;
        p.erase("ratings");
        p["matches"]["questions"] = questions;
    });
    const std::string shooter = editedProtocol(source, "shooter-quick.json", [&](nlohmann::json& p) {
        p["format_version"] = protocol::kShooterQuestionsSince;
        p["test"]["interleave"] = false;
        p["test"]["questions"] = nlohmann::json::array({questions[1]});
    });
    for (const std::string& path : {click, shooter}) {
        runner::HeadlessRun run;
        run.protocolPath = path;
        run.participant = "Q";
        run.resultsDir = results;
        run.player = "bot:11";
        run.seed = 11;
        std::ostringstream quiet;
        runner::runHeadless(run, quiet);
    }
    const std::string out = scratch("answers/out");
    exportQuietly(results, out);
    const auto answers = readCsv(out + "/answers.csv");
    std::map<std::string, std::vector<std::map<std::string, std::string>>> byGame;
    for (const auto& a : answers) byGame[a.at("game")].push_back(a);

    // Click: three answers after each match of the scored round.
    const auto& clicks = byGame["click"];
    const auto matches = readCsv(out + "/matches.csv");
    ASSERT_FALSE(matches.empty());
    ASSERT_EQ(clicks.size(), 3u * matches.size());
    for (std::size_t i = 0; i < clicks.size(); ++i) {
        const auto& a = clicks[i];
        EXPECT_EQ(a.at("block"), "scored");
        EXPECT_EQ(a.at("scored_phase"), "true");
        EXPECT_EQ(a.at("question_index"), std::to_string(i % 3));
        EXPECT_EQ(a.at("question_id"), questions[i % 3]["id"].get<std::string>());
        EXPECT_EQ(a.at("kind"), questions[i % 3]["kind"].get<std::string>());
        EXPECT_EQ(a.at("prompt"), questions[i % 3]["prompt"].get<std::string>());
        EXPECT_EQ(a.at("condition"), matches[i / 3].at("condition"));
        EXPECT_EQ(a.at("block_index"), matches[i / 3].at("match"));
        EXPECT_GE(std::stod(a.at("answer_s")), 0.5);  // the settle time, then the bot's reading
    }
    EXPECT_EQ(clicks[0].at("scale_min"), "0");
    EXPECT_EQ(clicks[0].at("scale_max"), "10");
    EXPECT_EQ(clicks[0].at("text"), "");
    EXPECT_EQ(clicks[1].at("scale_min"), "1");
    EXPECT_EQ(clicks[1].at("scale_max"), "3");
    EXPECT_EQ(clicks[1].at("value"), "2");  // the bot's choice for the second question: the second option
    EXPECT_EQ(clicks[1].at("text"), "the one before");
    EXPECT_EQ(clicks[2].at("value"), "");  // text has no number, nor a scale
    EXPECT_EQ(clicks[2].at("scale_min"), "");
    EXPECT_EQ(clicks[2].at("text"), "typed by a bot");
    EXPECT_EQ(clicks[2].at("answered_with"), "typed");
    // The Likert answers are the matches' ratings.
    const auto ratings = readCsv(out + "/ratings.csv");
    ASSERT_EQ(ratings.size(), matches.size());
    EXPECT_EQ(ratings[0].at("statement"), "It was fun");
    EXPECT_EQ(ratings[0].at("value"), clicks[0].at("value"));

    // Shooter: one answer after each condition's block, about that condition.
    const auto& shots = byGame["shooter"];
    ASSERT_EQ(shots.size(), 3u);
    std::vector<std::string> conditions;
    for (std::size_t i = 0; i < shots.size(); ++i) {
        EXPECT_EQ(shots[i].at("block"), "test");
        EXPECT_EQ(shots[i].at("block_index"), std::to_string(i));
        EXPECT_EQ(shots[i].at("kind"), "choice");
        conditions.push_back(shots[i].at("condition"));
    }
    EXPECT_EQ(conditions, (std::vector<std::string>{"conv15", "conv120", "warp15to120"}));
}

// Click sessions of older formats log their ratings as "rating" events: answers.csv has them too,
// without ids or answer times.
TEST(Export, OlderClickRatingsAreAnswersToo) {
    const std::string results = scratch("old-answers/results");
    headless("click-quick.json", "R", results, 3);
    const std::string out = scratch("old-answers/out");
    exportQuietly(results, out);
    const auto answers = readCsv(out + "/answers.csv");
    const auto ratings = readCsv(out + "/ratings.csv");
    ASSERT_FALSE(ratings.empty());
    ASSERT_EQ(answers.size(), ratings.size());
    for (std::size_t i = 0; i < answers.size(); ++i) {
        EXPECT_EQ(answers[i].at("kind"), "likert");
        EXPECT_EQ(answers[i].at("question_id"), "");
        EXPECT_EQ(answers[i].at("answer_s"), "");
        EXPECT_EQ(answers[i].at("prompt"), ratings[i].at("statement"));
        EXPECT_EQ(answers[i].at("value"), ratings[i].at("value"));
        EXPECT_EQ(answers[i].at("block_index"), ratings[i].at("match"));
    }
}

TEST(Export, AMissingOrEmptyResultsFolderIsNamed) {
    const std::string out = scratch("errors/out");
    try {
        exportQuietly("/nonexistent/results", out);
        ADD_FAILURE() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("'/nonexistent/results' does not exist"), std::string::npos) << e.what();
    }
    const std::string empty = scratch("errors/empty");
    try {
        exportQuietly(empty, out);
        ADD_FAILURE() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("holds no session files"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(fs::is_empty(out)) << "nothing is written when there is nothing to export";
}

// `export DIR` of a plan's folder (its sessions in DIR/results) finds the plan in DIR itself,
// not in DIR's parent, and writes participants.csv as `export DIR/results` does.
TEST(Export, ThePlansOwnFolderExportsWithItsParticipants) {
    const std::string dir = scratch("plan-folder/study");
    const plan::StudyPlan made =
        plan::makePlan(dir, {std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-quick.json"}, 2, {"A", "B"}, 3);
    plan::writePlan(dir, made);
    fs::create_directories(dir + "/results");
    runner::HeadlessRun run;
    run.protocolPath = dir + "/" + made.protocols.front().file;
    run.protocolText = plan::participantProtocolJson(dir, made, made.participants.front(), 0);
    run.planId = made.id;
    run.participant = "A";
    run.resultsDir = dir + "/results";
    run.player = "bot:1";
    run.seed = made.participants.front().seed;
    std::ostringstream quiet;
    runner::runHeadless(run, quiet);

    for (const std::string& exported : {dir, dir + "/results"}) {
        const std::string out = scratch(exported == dir ? "plan-folder/out-of-plan" : "plan-folder/out-of-results");
        std::string log;
        exportQuietly(exported, out, {}, &log);
        EXPECT_EQ(log.find("there is no"), std::string::npos) << exported << ": " << log;
        ASSERT_TRUE(fs::exists(out + "/participants.csv")) << exported << ": " << log;
        const auto rows = readCsv(out + "/participants.csv");
        ASSERT_EQ(rows.size(), 2u) << exported;
        EXPECT_EQ(rows[0].at("participant"), "A");
        EXPECT_EQ(rows[0].at("status"), "shooter-quick: done") << exported;
        EXPECT_EQ(rows[1].at("status"), "shooter-quick: not started") << exported;
    }
}

// Who played every row (a person, a bot), and where each condition came in the participant's order,
// so that a model can keep people apart and fit order effects without deriving them from `trial`.
TEST(Export, EveryRowSaysWhoPlayedAndWhereItsConditionCameInTheOrder) {
    const std::string source = scratch("kinds/source"), results = scratch("kinds/results");
    auto protocol = nlohmann::json::parse(slurp(std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-quick.json"));
    protocol["test"]["conditions"] = {"warp15to120", "conv120"};  // conv15: training's low condition only
    protocol["test"]["interleave"] = false;
    const std::string file = source + "/blocked.json";
    std::ofstream(file) << protocol.dump(2);
    runner::HeadlessRun run;
    run.protocolPath = file;
    run.participant = "P02";
    run.resultsDir = results;
    run.player = "bot:4";
    run.seed = 4;
    std::ostringstream quiet;
    const std::string bot = runner::runHeadless(run, quiet);
    replayedAs(bot, results, "P01", "human (cm_per_360=0, dpi=800, invert_y=0)");

    const std::string out = scratch("kinds/out");
    exporter::ExportOptions all;
    all.allPhases = true;
    exportQuietly(results, out, all);
    const std::map<std::string, std::string> kindOf{{"P01", "human"}, {"P02", "bot"}};
    int test = 0, training = 0;
    for (const auto& r : readCsv(out + "/shots.csv")) {
        EXPECT_EQ(r.at("player_kind"), kindOf.at(r.at("participant")));
        if (r.at("scored_phase") == "true") {
            // Blocked: the protocol's order, which a plan's condition_order writes into it.
            EXPECT_EQ(r.at("condition_position"), r.at("condition") == "warp15to120" ? "1" : "2") << r.at("trial");
            ++test;
        } else {
            EXPECT_EQ(r.at("condition_position"), "") << r.at("phase");
            ++training;
        }
    }
    EXPECT_GT(test, 0);
    EXPECT_GT(training, 0);
    for (const char* name : {"/hitrates.csv", "/pacing.csv", "/sessions.csv"})
        for (const auto& r : readCsv(out + name))
            EXPECT_EQ(r.at("player_kind"), kindOf.at(r.at("participant"))) << name;
    // The human's turn as it played: cm_per_360=0 is the protocol's own 0.0022 rad per count at
    // 800 counts per inch, 2 pi / 0.0022 / 800 inches.
    for (const auto& r : readCsv(out + "/sessions.csv")) {
        if (r.at("participant") == "P01")
            EXPECT_NEAR(std::stod(r.at("cm_per_360")), 2 * M_PI / 0.0022 / 800 * 2.54, 1e-9);
        else
            EXPECT_EQ(r.at("cm_per_360"), "");
    }
    std::map<std::string, std::string> usedIn;
    for (const auto& r : readCsv(out + "/conditions.csv")) usedIn[r.at("condition")] = r.at("used_in");
    EXPECT_EQ(
        usedIn,
        (std::map<std::string, std::string>{{"conv120", "test"}, {"conv15", "training"}, {"warp15to120", "test"}}));
}

TEST(Export, AnOutputFolderThatCannotBeMadeSaysWhy) {
    // The folder first: scratch() empties what it names, so the results inside come after.
    const std::string inTheWay = scratch("no-out") + "/a-file";
    const std::string results = scratch("no-out/results");
    headless("shooter-quick.json", "P01", results, 1);
    std::ofstream(inTheWay) << "not a folder\n";
    try {
        exportQuietly(results, inTheWay + "/out");
        FAIL() << "exported under a file";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("cannot create the output folder '" + inTheWay + "/out': Not a directory"),
                  std::string::npos)
            << e.what();
    }
}

// ============================ the documented columns ============================

// shots.csv: export.md documents the columns every game has, each game's page its own, which
// the file has after aim_time_s, game by game in the order they were registered.
void expectShotColumnsMatchTheirPages(const exporter::CsvColumns& csv, const std::vector<std::string>& pages) {
    std::vector<std::string> shared = csv.columns, games;
    const auto own = game::gameShotColumns();
    for (const auto& [gameName, columns] : own) {
        games.insert(games.end(), columns.begin(), columns.end());
        for (const std::string& c : columns) shared.erase(std::find(shared.begin(), shared.end(), c));
    }
    ASSERT_GE(games.size(), 4u) << "the shooter's three and the click game's one";
    const auto after = std::find(csv.columns.begin(), csv.columns.end(), "aim_time_s") + 1;
    EXPECT_EQ(std::vector<std::string>(after, after + static_cast<std::ptrdiff_t>(games.size())), games);
    std::size_t pagesOfGames = 0;
    for (const std::string& page : pages) {
        // A test game's page is held to its columns by its own tests, where it is registered.
        if (page.find("/tests/games/") != std::string::npos) continue;
        const std::vector<std::string> documented = testing_docs::documentedColumns(csv.file, page).columns;
        if (fs::path(page).filename() == "export.md") {
            EXPECT_EQ(documented, shared) << page;
            continue;
        }
        ++pagesOfGames;
        EXPECT_TRUE(std::any_of(own.begin(), own.end(), [&](const auto& g) { return g.second == documented; }))
            << page << " documents shots.csv columns no registered game has";
    }
    // A game without columns of its own (the discrimination task, which has no shots) has none
    // to document.
    const auto withColumns = std::count_if(own.begin(), own.end(), [](const auto& g) { return !g.second.empty(); });
    EXPECT_EQ(pagesOfGames, static_cast<std::size_t>(withColumns)) << "each game's own columns on its page";
}

// The page analysts read is the contract: each CSV's documented columns are exactly the
// columns its table writes, in the same order.
TEST(ExportColumns, MatchTheirPages) {
    const auto written = exporter::exportColumns();
    // Export's 11, the click game's matches.csv and ratings.csv, and the discrimination task's
    // discrimination_trials.csv and thresholds.csv.
    ASSERT_EQ(written.size(), 15u);
    for (const exporter::CsvColumns& csv : written) {
        const std::vector<std::string> pages = testing_docs::pagesDocumenting(csv.file);
        if (csv.file == "shots.csv") {
            expectShotColumnsMatchTheirPages(csv, pages);
            continue;
        }
        ASSERT_EQ(pages.size(), 1u) << csv.file << ": documented on one page";
        SCOPED_TRACE(pages.front() + ", " + csv.file);
        const testing_docs::DocumentedColumns documented = testing_docs::documentedColumns(csv.file, pages.front());
        EXPECT_EQ(documented.columns, csv.columns);
        EXPECT_EQ(documented.numbered, csv.numbered);
    }
}

}  // namespace
}  // namespace warplab::app
