// The session store: one SQLite file per session, written while the session runs, that
// survives a kill at any instant with every committed trial intact (DESIGN.md "Session data").
// The schema, its version and how to query it are documented in docs/session-format.md.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "session/rows.h"

namespace warplab::session {

// Bad or unreadable session files and results folders: one sentence naming the path.
class SessionError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Doubles round-trip bit for bit (-0.0 and infinities included); NaN is stored as SQL NULL
// and reads back as a quiet NaN.
class SessionWriter {
public:
    // Creates RESULTS/<participant>_<start time>[-N].warplab-session (SQLite, WAL) and commits
    // the header. Only [A-Za-z0-9_-] of the participant id reach the file name; the raw id is
    // kept in the header only. Throws SessionError naming the path, before creating anything,
    // when the results folder is missing or unwritable.
    // `first`: rows the session starts with (a resumed session's kept frames, runner/resume.h),
    // its first commit, written with the header before the file takes its name: a kill while
    // it is created leaves no session or one holding them all. Checked as the add* calls check.
    struct FirstCommit {
        std::vector<InputRecord> inputs;
        std::vector<FrameRecord> frames;
        std::vector<EventRecord> events;
    };
    static SessionWriter create(const std::string& resultsDir, const SessionHeader& header,
                                const FirstCommit& first = {});

    SessionWriter(SessionWriter&&) noexcept;
    SessionWriter& operator=(SessionWriter&&) noexcept;
    SessionWriter(const SessionWriter&) = delete;
    SessionWriter& operator=(const SessionWriter&) = delete;
    // Closes the file; whatever was added after the last commit is discarded, as in a crash.
    // Held commits get one last try of up to 2 s to be written.
    ~SessionWriter();

    const std::string& path() const;

    // Frame numbers must increase from one input (or frame) record to the next, so that a
    // table's rows in key order are the order they were committed in. Violations, and a
    // detailJson that is not a JSON object, throw std::invalid_argument.
    void addInput(const InputRecord& record);
    void addFrame(const FrameRecord& record);
    void addEvent(const EventRecord& record);

    // Makes everything added since the last commit ONE commit and writes it, with any
    // commits still held, as one durable transaction: a kill or a power cut afterwards keeps
    // it. Call it at the end of every trial and phase change.
    // Never waits, so a live session keeps its frame rate: while another program holds the
    // file's write lock (a DB browser, `sqlite3` without -readonly, a script's BEGIN
    // IMMEDIATE), it returns false and the commit is held in memory, in order, to be written
    // by the next commit(), close() or finish() that gets the lock. heldCommits() says how
    // many wait; a kill meanwhile loses them, so the supervisor must be told.
    // After writing, the file is read back (the header's checksum, the last commit and its
    // rows): another program may have emptied, cut, copied over or put back an old copy of it
    // while the commit was fsynced, which no stamp taken afterwards can tell from the writer's
    // own doing. Anything that differs, and any other write failure, saves every commit again
    // beside the file and goes on there (takeNotices() says so). Only when even that cannot be
    // written (disk full ...) does it throw SessionError; the commit stays held.
    bool commit();
    std::size_t heldCommits() const;
    double heldForSeconds() const;  // since the oldest held commit; 0 when none is held
    // What close() and finish() call about once a second while they wait.
    enum class WaitingFor {
        WriteLock,  // another program holds the write lock: nothing can be written
        Readers,  // finish(): a reader's open transaction keeps the last commits in the -wal
    };
    using WaitCallback = std::function<void(double secondsWaited, WaitingFor what)>;
    // The end of a session that did not run to its end: commit(), then wait as long as it
    // takes until every held commit is written (calling waiting(seconds, WaitingFor::WriteLock)
    // about once a second), then read the whole file back and compare it with every commit,
    // flag and summary written. If it differs, every commit is saved again beside it. Throws
    // SessionError, in one sentence saying what happened and where the whole session is, when
    // the session is no longer under the name it was created with (path() says where it is):
    // whatever the run did, its file was overwritten or taken, so it must not end as if all
    // were well. Adding or committing afterwards is a std::logic_error.
    void close(const WaitCallback& waiting = {});
    // What the supervisor must hear at once, each returned once: the session file or its
    // -wal deleted, replaced or overwritten in place by another program while it was written
    // (the writer then writes every commit again under the name, or beside it, and flags the
    // session; see docs/session-format.md, "Files replaced under a running session").
    std::vector<std::string> takeNotices();
    // Marks the session for its analysts (meta key "flag:<name>", written with the next
    // commit; a later flag of the same name replaces it), e.g. "missed_frames". Not part of
    // the header checksum: a flag describes how the session went, not what it ran.
    void flag(const std::string& name, const std::string& text);
    // A summary of how the session went for its analysts (meta key "summary:<name>", written
    // with the next commit; a later one of the same name replaces it), e.g. "pacing"
    // (session/pacing.h). Like a flag, not part of any checksum, and it changes no outcome.
    void summarize(const std::string& name, const std::string& text);
    // commit(), mark the session complete (meta key "completed_at") and fold the WAL into
    // the file, leaving one self-contained file. Waits for the write lock like close(). A
    // reader in a transaction (export, replay, a DB browser, a sqlite3 script) keeps the
    // commits made since it began out of the file; finish waits for it up to foldWaitS,
    // calling waiting(seconds, WaitingFor::Readers), and then writes the whole session again
    // into a new file that takes the name (the reader keeps the one it has open). Either way
    // the file alone is the whole session when finish returns. The -wal is removed where no
    // other program has the file open. Then the whole file is read back and checked, and
    // SessionError thrown, as close() does. Adding or committing afterwards is a
    // std::logic_error.
    static constexpr double kFoldWaitS = 2.0;
    void finish(const WaitCallback& waiting = {}, double foldWaitS = kFoldWaitS);

private:
    struct Impl;
    explicit SessionWriter(std::unique_ptr<Impl> impl);
    Impl& impl(const char* caller) const;
    std::unique_ptr<Impl> impl_;
};

struct SessionData {
    SessionHeader header;
    std::vector<InputRecord> inputs;
    std::vector<FrameRecord> frames;
    std::vector<EventRecord> events;  // in the order they were added
    bool completed = false;  // finish() was committed and nothing was lost to damage
    // Committed data was lost or altered (a row or commit failing its checksum, a cut-off
    // table): `note` says where reading stopped. An incomplete session that is not damaged
    // (killed, or still running) holds every trial it committed.
    bool damaged = false;
    std::map<std::string, std::string> flags;  // SessionWriter::flag()s, by name
    std::map<std::string, std::string> summaries;  // SessionWriter::summarize()s, by name
    std::string note;  // "" when complete; else why not and where it ends
};

// What a study's status needs of a session (plan/status.h), read from its header, its last
// commit and its events without reading its input and frame rows, which hold nearly all of a
// long session's bytes: readSessionOutline's cost does not grow with the session's length.
// For a session that is not damaged, every field is what readSession says. Damage is seen as
// far as the last commit shows it: its rows missing or rows after it (a file cut short, a
// -wal that fails its checksum or is another session's), an unreadable commits or events
// table, an event of the wrong type. A row altered in place, its commit's checksum failing,
// only readSession finds: it checks every commit (replay, export and resume read so).
struct SessionOutline {
    SessionHeader header;
    std::vector<EventRecord> events;  // those of the last commit and the ones before, unchecked
    bool completed = false;  // finish() was committed and no damage was seen
    bool damaged = false;
    std::map<std::string, std::string> flags;  // SessionWriter::flag()s, by name
    std::map<std::string, std::string> summaries;  // SessionWriter::summarize()s, by name
    std::string note;  // "" when complete; else why not and where it ends
    // As the last commit counts them: the commits, and the input and frame rows up to it.
    std::int64_t commits = 0, inputRows = 0, frameRows = 0;
};

// Who played a session, from its header's `player`: "human" (a person in a window), "bot",
// "simulated" (a simulated participant, `sim:SEED`) or "replay" (another session's input).
// The one place the kinds are named: export's per-trial and per-participant files, study
// status and the report all say it so, and the analysis keeps people apart from the rest.
// "" for a `player` none of these (a file written by a later warplab).
std::string playerKind(const std::string& player);

// Now, as the store writes its times: ISO 8601 UTC with milliseconds, e.g. 2024-05-01T12:34:56.789Z.
std::string utcNow();

// Opens read-only (a running session may be read too). Checks the format version and schema.
// A truncated or corrupted file yields the commits before the damage, each checked against
// its checksum, and a note saying where it stopped. Throws SessionError naming the path for
// a file that is missing, not a SQLite database, not a warplab session, another format
// version, or whose header is unreadable or fails its checksum.
SessionData readSession(const std::string& path);
// Only the header (checked against its checksum), without reading the records: for telling
// which sessions a folder holds. Throws SessionError as readSession does for the header.
SessionHeader readSessionHeader(const std::string& path);
// The header, the last commit and the events (SessionOutline): how a session ended and how far
// it got, for telling where a study stands. Throws SessionError as readSession does.
SessionOutline readSessionOutline(const std::string& path);

}  // namespace warplab::session
