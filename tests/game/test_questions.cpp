// The questions after a block, in both games: each kind answers as docs/protocol.md says (a
// digit or a click after the settle time, typed text ended by Enter), its answer is logged as an
// "answer" event naming the question and the block, a session with typed answers replays from
// its input record event for event, and the bots answer every kind so that a session ends.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "click_bot.h"
#include "click_game.h"
#include "click/click_protocol.h"
#include "shooter/shooter_protocol.h"
#include "game/questionnaire.h"
#include "session/records.h"
#include "shooter_bot.h"
#include "shooter_game.h"

namespace warplab::game {
namespace {

using protocol::Question;
using protocol::QuestionKind;

const DisplaySize kDisplay{1280, 720};

nlohmann::json detail(const session::EventRecord& e) { return nlohmann::json::parse(e.detailJson); }

Question likert(const char* id, int min, int max) {
    Question q;
    q.id = id;
    q.prompt = std::string("How was it? (") + id + ")";
    q.min = min;
    q.max = max;
    q.minLabel = "awful";
    q.maxLabel = "great";
    return q;
}
Question choice(const char* id, std::vector<std::string> options) {
    Question q;
    q.id = id;
    q.kind = QuestionKind::Choice;
    q.prompt = "Which was it?";
    q.options = std::move(options);
    return q;
}
Question text(const char* id, int maxLength = protocol::kMaxTextAnswerBytes) {
    Question q;
    q.id = id;
    q.kind = QuestionKind::Text;
    q.prompt = "Anything else?";
    q.maxLength = maxLength;
    return q;
}

std::vector<Question> everyKind() {
    return {likert("fun", 0, 10), choice("which", {"the first", "the second", "neither"}), text("comment")};
}

// ---------------------------------------------------------------- typed text

TEST(QuestionText, TypedTextIsEditedAsAParticipantExpects) {
    EXPECT_EQ(editedAnswer("", "smooth", 200), "smooth");
    EXPECT_EQ(editedAnswer("smooth", "\b\b\bky", 200), "smoky");
    // Backspace takes back a whole character, however many bytes it has.
    EXPECT_EQ(editedAnswer("", "caf\xC3\xA9\b\xC3\xA8", 200), "caf\xC3\xA8");
    EXPECT_EQ(editedAnswer("", "a\xF0\x9F\x98\x80\b", 200), "a");
    EXPECT_EQ(editedAnswer("", "\b\b", 200), "");
    // Control characters (a tab, a stray Enter, DEL) never reach the answer.
    EXPECT_EQ(editedAnswer("", "a\tb\rc\x7F", 200), "abc");
}

// Each screen says how it is answered, as step() takes answers: a scale's digit keys only for
// its values that have one. The Likert screen said nothing.
TEST(QuestionText, EachScreenSaysHowItIsAnswered) {
    const std::vector<Question> questions{likert("seven", 1, 7), likert("eleven", 0, 10), likert("far", 10, 20),
                                          choice("which", {"a", "b"}), text("comment")};
    Questionnaire list(questions, 120.0, kDisplay, false);
    list.open(0);
    const std::vector<std::string> said{"Click a box, or press 1\u20137, to answer",
                                        "Click a box, or press 1\u20139 for those values, to answer",
                                        "Click a box to answer", "Click an option, or press its number, to answer",
                                        "Type your answer, then press Enter"};
    for (std::size_t i = 0; i < questions.size(); ++i) {
        QuestionPrompt shown = list.prompt({0.0, 0.0});
        EXPECT_EQ(shown.hint, said[i]) << questions[i].id;
        // Answer it (past the settle time) to reach the next one.
        const std::uint32_t keys = questions[i].kind == QuestionKind::Text ? kKeyEnter : digitKey(1);
        const auto frame = static_cast<std::int64_t>(2 * 120 * (i + 1));
        if (questions[i].kind == QuestionKind::Likert && questions[i].min > 9) {
            shown.highlighted = 0;
            ASSERT_TRUE(list.step(frame, shown, 0, true, ""));
        } else {
            ASSERT_TRUE(list.step(frame, shown, keys, false, "")) << questions[i].id;
        }
    }
}

TEST(QuestionText, AnAnswerIsAlwaysValidUtf8WithinItsLength) {
    // Bytes no character is made of: a lone continuation byte, a cut-off sequence, an overlong
    // form, a surrogate, 0xFF.
    EXPECT_EQ(editedAnswer("",
                           "a\x80"
                           "b\xC3"
                           "c\xC0\xAF"
                           "d\xED\xA0\x80"
                           "e\xFF",
                           200),
              "abcde");
    // The limit is in bytes and never splits a character: what does not fit is dropped.
    EXPECT_EQ(editedAnswer("abc", "d\xC3\xA9", 4), "abcd");
    EXPECT_EQ(editedAnswer("abc", "\xC3\xA9", 5), "abc\xC3\xA9");
    EXPECT_EQ(editedAnswer("abcd", "\bx", 4), "abcx");  // room made by Backspace is usable
    // What nlohmann::json writes without throwing: the event detail of such an answer.
    const std::string answer = editedAnswer("",
                                            "\xF4\x90\x80\x80"
                                            "ok\xE0\x80\x80",
                                            200);
    EXPECT_EQ(answer, "ok");
    EXPECT_NO_THROW(nlohmann::json(answer).dump());
}

// ---------------------------------------------------------------- click game

protocol::ClickProtocol clickWith(std::vector<Question> questions) {
    auto p = protocol::loadClickProtocol(std::string(WARPLAB_SOURCE_DIR) + "/protocol/click-quick.json");
    p.formatVersion = protocol::kClickQuestionsSince;  // logs "answer" events
    p.conditions = {"conv60", "conv30"};
    p.rounds = {{"practice", false, 1, ""}, {"scored", true, 1, ""}};
    p.shuffle = false;
    p.matchS = 0.5;
    p.questions = std::move(questions);
    return p;
}

std::vector<session::EventRecord> answersIn(std::vector<session::EventRecord> events) {
    events.erase(std::remove_if(events.begin(), events.end(), [](const auto& e) { return e.type != "answer"; }),
                 events.end());
    return events;
}

// Steps through the ready screen and the first match to its first question.
ShownFrame firstQuestion(ClickGame& game) {
    ShownFrame shown = game.step({0, 0, 0, kKeyEnter});
    while (!shown.question) shown = game.step({});
    return shown;
}

void waitOutSettle(ClickGame& game, double refreshHz) {
    for (long i = 1; i < std::lround(kAnswerSettleS * refreshHz); ++i) game.step({});
}

glm::dvec2 centreOf(const glm::dvec4& box) { return {box.x + box.z / 2, box.y + box.w / 2}; }

TEST(ClickQuestions, EachKindAnswersAsDocumentedAndIsLoggedAsAnAnswer) {
    const auto p = clickWith(everyKind());
    ClickGame game(p, 1, kDisplay);
    ShownFrame shown = firstQuestion(game);
    game.takeEvents();

    // Likert 0..10: eleven boxes labelled with their values, the ends labelled; a digit answers.
    ASSERT_EQ(shown.question->kind, QuestionKind::Likert);
    EXPECT_EQ(shown.question->boxes.size(), 11u);
    EXPECT_EQ(shown.question->boxLabels.front(), "0");
    EXPECT_EQ(shown.question->boxLabels.back(), "10");
    EXPECT_EQ(shown.question->minLabel, "awful");
    EXPECT_EQ(shown.question->count, 3);
    for (const auto& b : shown.question->boxes) {  // the row fits the display
        EXPECT_GE(b.x, 0.0);
        EXPECT_LE(b.x + b.z, kDisplay.width);
    }
    game.step({0, 0, 0, digitKey(7)});  // within the settle time: dropped
    game.step({});
    waitOutSettle(game, p.refreshHz);
    shown = game.step({0, 0, 0, digitKey(7)});
    auto events = game.takeEvents();
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].type, "answer");
    EXPECT_EQ(events[0].phase, "practice");
    EXPECT_EQ(events[0].trial, 0);
    EXPECT_EQ(events[0].condition, "conv60");
    auto d = detail(events[0]);
    EXPECT_EQ(d["question_id"], "fun");
    EXPECT_EQ(d["question_index"], 0);
    EXPECT_EQ(d["kind"], "likert");
    EXPECT_EQ(d["value"], 7);
    EXPECT_FALSE(d.contains("text"));
    EXPECT_EQ(d["answered_with"], "key");
    EXPECT_EQ(d["round"], "practice");
    EXPECT_EQ(d["scored"], false);
    EXPECT_GE(d["answer_s"].get<double>(), kAnswerSettleS);

    // Choice: a box per option, labelled with it; a click on the second answers 2.
    shown = game.step({});
    ASSERT_EQ(shown.question->kind, QuestionKind::Choice);
    ASSERT_EQ(shown.question->boxLabels, (std::vector<std::string>{"the first", "the second", "neither"}));
    waitOutSettle(game, p.refreshHz);
    const glm::dvec2 move = centreOf(shown.question->boxes[1]) - game.cursor();
    shown = game.step({move.x, move.y, 0, 0});
    EXPECT_EQ(shown.question->highlighted, 1);
    game.step({0, 0, kButtonLeft, 0});
    events = game.takeEvents();
    ASSERT_EQ(events.size(), 1u);
    d = detail(events[0]);
    EXPECT_EQ(d["kind"], "choice");
    EXPECT_EQ(d["value"], 2);
    EXPECT_EQ(d["text"], "the second");
    EXPECT_EQ(d["answered_with"], "mouse");

    // Text: typed over several frames, Backspace taking back a character; Enter ends it.
    shown = game.step({0, 0, 0, 0, "x"});  // the digit or click of the last answer: dropped
    ASSERT_EQ(shown.question->kind, QuestionKind::Text);
    EXPECT_EQ(shown.question->boxes.size(), 1u);
    waitOutSettle(game, p.refreshHz);
    game.step({0, 0, 0, 0, "too l"});
    game.step({0, 0, 0, 0, "ag\b\bate"});
    shown = game.step({0, 0, 0, 0, " \xE2\x80\x94 ok"});
    EXPECT_EQ(shown.question->typed, "too late \xE2\x80\x94 ok");
    EXPECT_TRUE(game.takeEvents().empty());  // no answer before Enter
    game.step({0, 0, 0, kKeyEnter});
    events = answersIn(game.takeEvents());  // the next match starts too
    ASSERT_EQ(events.size(), 1u);
    d = detail(events[0]);
    EXPECT_EQ(d["kind"], "text");
    EXPECT_EQ(d["text"], "too late \xE2\x80\x94 ok");
    EXPECT_EQ(d["answered_with"], "typed");
    EXPECT_FALSE(d.contains("value"));

    // The next match follows the last answer.
    shown = game.step({});
    EXPECT_FALSE(shown.question.has_value());
    EXPECT_EQ(shown.condition.name, "conv30");
}

TEST(ClickQuestions, ADigitOfAChoiceOutsideItsOptionsAnswersNothing) {
    const auto p = clickWith({choice("which", {"a", "b"})});
    ClickGame game(p, 1, kDisplay);
    firstQuestion(game);
    waitOutSettle(game, p.refreshHz);
    game.takeEvents();
    game.step({0, 0, 0, digitKey(3)});
    EXPECT_TRUE(game.takeEvents().empty());
    game.step({});
    game.step({0, 0, 0, digitKey(2)});
    const auto events = answersIn(game.takeEvents());
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(detail(events[0])["text"], "b");
}

struct Played {
    std::vector<FrameInput> inputs;
    std::vector<session::EventRecord> events;
    bool finished = false;
};

template <class G, class B>
Played play(G& game, B& bot) {
    Played out;
    FrameInput input;
    for (int i = 0; i < 2000000 && !game.finished(); ++i) {
        out.inputs.push_back(input);
        const ShownFrame shown = game.step(input);
        for (auto& e : game.takeEvents()) out.events.push_back(e);
        input = bot.next(shown);
    }
    out.finished = game.finished();
    return out;
}

template <class G>
std::vector<session::EventRecord> replay(G& game, const std::vector<FrameInput>& inputs) {
    std::vector<session::EventRecord> events;
    for (const auto& input : inputs) {
        game.step(input);
        for (auto& e : game.takeEvents()) events.push_back(e);
    }
    return events;
}

std::string eventDifference(const std::vector<session::EventRecord>& a, const std::vector<session::EventRecord>& b) {
    if (a.size() != b.size()) return std::to_string(a.size()) + " events against " + std::to_string(b.size());
    for (std::size_t i = 0; i < a.size(); ++i)
        if (const std::string d = session::firstDifference(a[i], b[i]); !d.empty())
            return "event " + std::to_string(i) + ": " + d;
    return "";
}

TEST(ClickQuestions, TheBotAnswersEveryKindAndTheSessionReplaysFromItsInput) {
    // A scale no digit reaches (-3..3) is answered with the cursor.
    const auto p = clickWith({likert("fun", -3, 3), choice("which", {"a", "b", "c"}), text("comment")});
    ClickGame game(p, 5, kDisplay);
    ClickBot bot(9, p, kDisplay);
    const Played played = play(game, bot);
    ASSERT_TRUE(played.finished);
    const auto answers = answersIn(played.events);
    ASSERT_EQ(answers.size(), 4u * 3u);  // four matches, three questions each
    for (std::size_t i = 0; i < answers.size(); ++i) {
        const auto d = detail(answers[i]);
        EXPECT_EQ(d["question_index"], static_cast<int>(i % 3));
        EXPECT_EQ(answers[i].trial, static_cast<int>(i / 3));
    }
    EXPECT_EQ(detail(answers[2])["text"], "typed by a bot");
    // The typed text is part of the input: played again, it gives the same events.
    ClickGame again(p, 5, kDisplay);
    EXPECT_EQ(eventDifference(replay(again, played.inputs), played.events), "");
    // ... and without it the text answers differ.
    std::vector<FrameInput> withoutText = played.inputs;
    for (auto& in : withoutText) in.text.clear();
    ClickGame blind(p, 5, kDisplay);
    EXPECT_NE(eventDifference(replay(blind, withoutText), played.events), "");
}

TEST(ClickQuestions, NoQuestionsGoesStraightToTheNextMatch) {
    const auto p = clickWith({});
    ClickGame game(p, 1, kDisplay);
    ClickBot bot(3, p, kDisplay);
    const Played played = play(game, bot);
    ASSERT_TRUE(played.finished);
    for (const auto& e : played.events) EXPECT_NE(e.type, "answer");
}

// ---------------------------------------------------------------- shooter

protocol::ShooterProtocol shooterWith(std::vector<Question> questions, bool interleave) {
    auto p = protocol::loadShooterProtocol(std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-quick.json");
    p.formatVersion = protocol::kShooterQuestionsSince;
    p.acclimationS = 0;
    p.training.timeLimitS = 2;
    p.targetsPerCondition = 2;
    p.interleaveConditions = interleave;
    p.questions = std::move(questions);
    return p;
}

TEST(ShooterQuestions, ABlockedTestAsksAfterEachConditionsBlock) {
    const auto p = shooterWith(everyKind(), /*interleave=*/false);
    ShooterGame game(p, 2, DisplaySize{});
    ShooterBot bot(4, p);
    const Played played = play(game, bot);
    ASSERT_TRUE(played.finished);
    // Answers come in threes, each after its block's last test trial and before the next
    // block's first, about that block's condition.
    std::vector<std::string> askedAbout;
    std::string lastTrialCondition;
    int trialsSince = 0;
    for (const auto& e : played.events) {
        if (e.phase != "test") continue;
        if (e.type == "shot" || e.type == "timeout") {
            if (e.condition != lastTrialCondition) {
                EXPECT_TRUE(lastTrialCondition.empty() || trialsSince == 0)
                    << "block of " << lastTrialCondition << " unasked";
                lastTrialCondition = e.condition;
            }
            ++trialsSince;
        } else if (e.type == "answer") {
            EXPECT_EQ(e.condition, lastTrialCondition);
            EXPECT_EQ(e.trial, static_cast<int>(askedAbout.size() / 3));
            askedAbout.push_back(e.condition);
            trialsSince = 0;
        }
    }
    EXPECT_EQ(askedAbout,
              (std::vector<std::string>{"conv15", "conv15", "conv15", "conv120", "conv120", "conv120", "warp15to120",
                                        "warp15to120", "warp15to120"}));
    ShooterGame again(p, 2, DisplaySize{});
    EXPECT_EQ(eventDifference(replay(again, played.inputs), played.events), "");
}

TEST(ShooterQuestions, AnInterleavedTestAsksOnceAtItsEnd) {
    const auto p = shooterWith({likert("fun", 1, 7)}, /*interleave=*/true);
    ShooterGame game(p, 2, DisplaySize{});
    ShooterBot bot(4, p);
    const Played played = play(game, bot);
    ASSERT_TRUE(played.finished);
    const auto answers = answersIn(played.events);
    ASSERT_EQ(answers.size(), 1u);
    EXPECT_EQ(answers[0].condition, "");  // the block mixed the conditions
    EXPECT_EQ(detail(answers[0])["value"], 4);  // the bot's Likert answer: the scale's middle
    // After the test's last trial, before it is done.
    const auto at =
        std::find_if(played.events.begin(), played.events.end(), [](const auto& e) { return e.type == "answer"; });
    int trialsAfter = 0;
    for (auto it = at; it != played.events.end(); ++it) trialsAfter += it->type == "shot" || it->type == "timeout";
    EXPECT_EQ(trialsAfter, 0);
    EXPECT_EQ(played.events.back().type, "phase");
}

TEST(ShooterQuestions, OnTheQuestionScreensTheMouseMovesACursorNotTheView) {
    const auto p = shooterWith({choice("which", {"a", "b"})}, /*interleave=*/true);
    ShooterGame game(p, 2, DisplaySize{});
    ShooterBot bot(4, p);
    FrameInput input;
    ShownFrame shown;
    while (!game.finished()) {
        shown = game.step(input);
        if (shown.question) break;
        input = bot.next(shown);
    }
    ASSERT_TRUE(shown.question.has_value());
    EXPECT_EQ(shown.pointer, PointerKind::Cursor);
    EXPECT_TRUE(shown.blank);
    const float yaw = shown.camera.yaw;
    const glm::dvec2 box = centreOf(shown.question->boxes[0]) - shown.cursor;
    shown = game.step({box.x / kQuestionCursorPixelsPerCount, box.y / kQuestionCursorPixelsPerCount, 0, 0});
    EXPECT_EQ(shown.camera.yaw, yaw);
    EXPECT_EQ(shown.question->highlighted, 0);
    for (int i = 0; i < 120; ++i) shown = game.step({});
    game.takeEvents();
    game.step({0, 0, kButtonLeft, 0});
    const auto events = game.takeEvents();
    ASSERT_GE(events.size(), 1u);
    EXPECT_EQ(events[0].type, "answer");
    EXPECT_EQ(detail(events[0])["text"], "a");
    EXPECT_EQ(events[0].phase, "test");
}

// The first frame of the first question screen of a test with one Likert question, format
// `version`.
ShownFrame firstLikertScreen(int version) {
    auto p = shooterWith({likert("fun", 1, 7)}, /*interleave=*/true);
    p.formatVersion = version;
    ShooterGame game(p, 2, DisplaySize{});
    ShooterBot bot(4, p);
    FrameInput input;
    ShownFrame shown;
    while (!game.finished()) {
        shown = game.step(input);
        if (shown.question) break;
        input = bot.next(shown);
    }
    return shown;
}

// From format 7 the Likert screen opens with no box under the cursor, so none is lit as if
// chosen (at the middle the cursor lay on the middle box); a format 5 or 6 file keeps the
// cursor where its sessions had it, so that they replay.
TEST(ShooterQuestions, TheLikertScreenOpensWithNoBoxUnderTheCursor) {
    const ShownFrame now = firstLikertScreen(protocol::kShooterRecentresSince);
    ASSERT_TRUE(now.question.has_value());
    EXPECT_EQ(now.question->highlighted, -1);
    for (const auto& box : now.question->boxes) EXPECT_LT(now.cursor.y, box.y) << "the cursor is above the row";
    EXPECT_EQ(now.question->hint, "Click a box, or press 1\u20137, to answer");
    const ShownFrame before = firstLikertScreen(protocol::kShooterRecentresSince - 1);
    ASSERT_TRUE(before.question.has_value());
    EXPECT_EQ(before.question->highlighted, 3) << "format 6 sessions replay with the cursor where it was";
}

// Where training and the test begin the view is the resting one again (targets spawn in it),
// whatever the participant looked at before; in the game, so replay sees it. Format 6 files
// keep the view as it was.
TEST(ShooterPhases, TheViewIsRecentredWhereTrainingAndTheTestBegin) {
    for (const int version : {protocol::kShooterRecentresSince, protocol::kShooterRecentresSince - 1}) {
        auto p = protocol::loadShooterProtocol(std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-quick.json");
        p.formatVersion = version;
        p.acclimationS = 0.5;
        p.supervisorStartsTest = false;
        ShooterGame game(p, 2, DisplaySize{});
        const float restingYaw = game.step({}).camera.yaw;
        // Look aside and up through the acclimation, then keep still: 20 frames into the
        // training (its instructions screen, or its first trial) the view is the phase's.
        std::int64_t trainingFrom = -1;
        ShownFrame shown;
        for (int i = 0; i < 400 && (trainingFrom < 0 || shown.frame < trainingFrom + 20); ++i) {
            shown = game.step(i < 30 ? FrameInput{40.0, -20.0, 0, 0} : FrameInput{});
            for (const auto& e : game.takeEvents())
                if (e.type == "phase" && e.phase == "training") trainingFrom = e.frame;
        }
        ASSERT_GE(trainingFrom, 30) << "version " << version;
        if (version >= protocol::kShooterRecentresSince)
            EXPECT_EQ(shown.camera.yaw, restingYaw) << "the training begins facing the targets";
        else
            EXPECT_NE(shown.camera.yaw, restingYaw) << "a format 6 session keeps the view it had";
    }
}

// A session resumed goes on facing the targets (format 7): the view is the resting one from the
// first frame after the resume point, whatever the participant looked at before it.
TEST(ShooterPhases, AResumedSessionGoesOnFacingTheTargets) {
    for (const int version : {protocol::kShooterRecentresSince, protocol::kShooterRecentresSince - 1}) {
        auto p = protocol::loadShooterProtocol(std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-quick.json");
        p.formatVersion = version;
        ShooterGame game(p, 2, DisplaySize{});
        const float restingYaw = game.step({}).camera.yaw;
        for (int i = 0; i < 30; ++i) game.step({40.0, -20.0, 0, 0});
        game.resumeHere();
        ShownFrame shown;
        for (int i = 0; i < 20; ++i) shown = game.step({});  // past any frame rendered before it
        if (version >= protocol::kShooterRecentresSince)
            EXPECT_EQ(shown.camera.yaw, restingYaw);
        else
            EXPECT_NE(shown.camera.yaw, restingYaw) << "a format 6 session goes on as it was";
    }
}

TEST(ShooterQuestions, NoneByDefault) {
    const auto p = protocol::loadShooterProtocol(std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-quick.json");
    EXPECT_TRUE(p.questions.empty());
    EXPECT_TRUE(protocol::ShooterProtocol{}.questions.empty());
}

}  // namespace
}  // namespace warplab::game
