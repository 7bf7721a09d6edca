// SessionWriter on the sqlite3 C API: the tables it writes are schema.h's.
#include "session/session_store.h"

#include "session/records.h"

#include "archive.h"
#include "checksum.h"
#include "connection.h"
#include "disk_check.h"
#include "file_stamp.h"
#include "naming.h"
#include "schema.h"
#include "sqlite_handles.h"

#include <sqlite3.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <deque>
#include <filesystem>
#include <map>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace warplab::session {
namespace {

namespace fs = std::filesystem;

// The store's shared pieces (sqlite_handles.h, schema.h, checksum.h, naming.h, archive.h).
using namespace detail;

// 128 random bits as 32 hex digits: two sessions never share one, a copy keeps it.
std::string newSessionId() {
    std::random_device random;
    std::string id;
    for (int i = 0; i < 4; ++i) {
        char part[9];
        std::snprintf(part, sizeof part, "%08x", static_cast<unsigned>(random()));
        id += part;
    }
    return id;
}

std::int64_t headerChecksum(const SessionHeader& h) {
    Checksum checksum;
    for (const auto& [key, value] : headerEntries(h)) {
        checksum.text(key);
        checksum.text(value);
    }
    return static_cast<std::int64_t>(checksum.value());
}

}  // namespace

struct SessionWriter::Impl {
    using Clock = std::chrono::steady_clock;

    std::string resultsDir, stem;  // where the session lives and its name without "-N" and extension
    std::string name;  // the path the session was created under, which the run announced
    // What took the session away from `name` (a rescue that saved it beside another
    // program's file there), in words; "" while the session is under its name.
    std::string movedAway;
    SessionHeader header;  // as written: the session id and start time filled in
    Connection live;  // to the session file at its name (live.path)
    bool finished = false;

    // Added since the last commit(): part of no commit yet, dropped as in a crash. Rows are
    // kept in memory until they are written, so another program's write lock can only delay
    // them (see commit()).
    CommitRows adding;
    CommitChecksum addingChecksum;
    // Meta entries written with the next commit (flags as "flag:<name>", summaries as
    // "summary:<name>"); then held, then written, as the rows are.
    std::map<std::string, std::string> addingFlags;
    std::optional<std::int64_t> lastInputFrame, lastFrameFrame;  // over every row added
    std::int64_t lastChecksum = 0;  // of the last commit made, the header's before the first

    // Commits made but not yet in the file, oldest first, and what goes with them.
    std::deque<CommitRows> held;
    std::map<std::string, std::string> heldFlags;
    bool completing = false;  // finish(): completed_at still to be written
    std::optional<Clock::time_point> heldSince;
    // Rows in every commit so far, written or held: a commit's counts are cumulative.
    std::int64_t inputRows = 0, frameRows = 0, eventRows = 0;

    // What is in the file: every commit, flag and the completion written, to write the
    // session again whole when the file cannot be trusted (rescue()).
    Archive written;
    CommitRows lastWritten;  // the newest commit in `written`, checked on disk after each write
    std::map<std::string, std::string> writtenFlags;
    std::string completedAt;

    // The session file and its -wal as this writer last left them (checkUntouched()), and the
    // file it opened (device and inode), whatever has been done to it since.
    std::optional<FileStamp> fileStamp, walStamp, ownFile;
    std::vector<std::string> notices;

    ~Impl() {
        // Held commits were committed as far as the game knows: one last short try to write
        // them. What was added after the last commit is dropped, as a crash would drop it.
        if (!live.db || (held.empty() && heldFlags.empty() && !completing)) return;
        try {
            const auto deadline = Clock::now() + std::chrono::seconds(2);
            while (!writeHeld() && Clock::now() < deadline) std::this_thread::sleep_for(std::chrono::milliseconds(20));
        } catch (...) {}
    }

    std::string hiddenPath(const char* work) const { return hiddenWorkPath(resultsDir, stem, work); }

    // Writes a session file at `temp`, a name no other program uses: the header, every commit
    // written so far and every one held, the flags and the completion, in one fsynced
    // transaction; then switches it to WAL mode when the session goes on writing there.
    // create() writes its first file so (nothing written or held yet), rescue() and finish()
    // the whole session again.
    void buildFile(const std::string& temp, bool wal) const {
        removeSessionFiles(temp);  // a leftover of a killed run with our pid
        Connection c;
        c.path = temp;
        c.open(SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, "creating");
        c.exec("PRAGMA synchronous=FULL", "setting synchronous");
        c.exec("BEGIN IMMEDIATE", "writing the header");
        c.exec(("PRAGMA application_id=" + std::to_string(kApplicationId)).c_str(), "writing the header");
        for (const char* sql : kSchema) c.exec(sql, "creating the tables");
        c.exec(inputTable().createSql().c_str(), "creating the tables");
        c.exec(frameTable().createSql().c_str(), "creating the tables");
        c.exec(eventTable().createSql().c_str(), "creating the tables");
        c.prepareInserts();
        written.forEach([&](const CommitRows& commit) { c.writeCommit(commit); });
        for (const CommitRows& commit : held) c.writeCommit(commit);
        std::map<std::string, std::string> meta = metaWritten();
        for (const auto& [key, text] : heldFlags) meta[key] = text;
        for (const auto& [key, text] : meta) c.putMeta(key, text);
        c.exec("COMMIT", "writing the file");
        // WAL mode is kept in the file: switching here, while nobody else can see the file,
        // means another program's lock on the named file can never stop the switch.
        if (wal) c.exec("PRAGMA journal_mode=WAL", "switching to WAL mode");
        c.close();  // the file is whole and fsynced
    }

    // The meta table as written: the header, its checksum, the header's extras, the flags and
    // summaries, and the completion once it is written.
    std::map<std::string, std::string> metaWritten() const {
        std::map<std::string, std::string> meta(writtenFlags);
        for (const auto& [key, value] : headerEntries(header)) meta[key] = value;
        meta["header_checksum"] = headerChecksumText();
        for (const auto& [key, value] : headerExtras(header)) meta[key] = value;
        if (!completedAt.empty()) meta["completed_at"] = completedAt;
        return meta;
    }
    std::string headerChecksumText() const { return numberText(static_cast<std::uint64_t>(headerChecksum(header))); }

    // Everything held is now in the file (buildFile() or writeHeld() wrote it).
    void heldAreWritten(const std::string& completionTime) {
        for (CommitRows& commit : held) written.append(commit);
        if (!held.empty()) lastWritten = std::move(held.back());
        held.clear();
        for (auto& [name, text] : heldFlags) writtenFlags[name] = std::move(text);
        heldFlags.clear();
        if (completing) completedAt = completionTime;
        completing = false;
        heldSince.reset();
    }

    // Opens `live.path` (which holds at least the header) for appending: WAL, fsync per
    // commit, statements prepared. Also used to go on in a file written again by rescue().
    void openForWriting() {
        live.open(SQLITE_OPEN_READWRITE, "opening");
        // No busy wait inside SQLite: a foreign write lock must not stall a live frame. The
        // writer holds its commits and retries instead (commit(), close(), finish()).
        sqlite3_busy_timeout(live.db.get(), 0);
        // WAL: a commit appends to the log, so a kill mid-commit leaves the previous commit
        // intact, and analysts can read a running session. FULL: each commit is fsynced, so
        // a power cut keeps it as well; one fsync per trial costs nothing next to a
        // participant's hour (see docs/session-format.md).
        sqlite3_stmt* rawMode = nullptr;
        sqlite3_prepare_v2(live.db.get(), "PRAGMA journal_mode=WAL", -1, &rawMode, nullptr);
        Stmt mode(rawMode);
        if (!mode || sqlite3_step(mode.get()) != SQLITE_ROW || columnText(mode.get(), 0) != "wal")
            live.fail("switching to WAL mode");
        mode.reset();
        live.exec("PRAGMA synchronous=FULL", "setting synchronous");
        live.prepareInserts();
        stampFiles();
        ownFile = fileStamp;
    }

    // Makes the rows added since the last commit one commit, held until it is written.
    void commitAdded() {
        const bool rows = !adding.inputs.empty() || !adding.frames.empty() || !adding.events.empty();
        for (auto& [name, text] : addingFlags) heldFlags[name] = std::move(text);
        addingFlags.clear();
        if (!rows) return;
        CommitRows h = std::move(adding);
        adding = CommitRows{};
        h.inputRows = inputRows += static_cast<std::int64_t>(h.inputs.size());
        h.frameRows = frameRows += static_cast<std::int64_t>(h.frames.size());
        h.eventRows = eventRows += static_cast<std::int64_t>(h.events.size());
        h.lastFrame = lastInputFrame;
        if (lastFrameFrame && (!h.lastFrame || *lastFrameFrame > *h.lastFrame)) h.lastFrame = lastFrameFrame;
        h.checksum = lastChecksum = addingChecksum.value(lastChecksum);
        h.committedAt = utcNow();
        addingChecksum = CommitChecksum{};
        held.push_back(std::move(h));
        if (!heldSince) heldSince = Clock::now();
    }

    // Writes every held commit, in order, then the held flags and completed_at, as ONE
    // transaction (fsynced). False, with nothing written, while another connection holds the
    // write lock; any other failure throws SessionError and keeps everything held.
    bool writeHeld() {
        if (held.empty() && heldFlags.empty() && !completing) return true;
        if (checkUntouched(true)) return true;  // rescue() wrote everything held
        const std::string completionTime = completing ? utcNow() : completedAt;
        live.writing = true;
        try {
            live.exec("BEGIN IMMEDIATE", "starting a transaction");
            for (const CommitRows& h : held) live.writeCommit(h);
            for (const auto& [key, text] : heldFlags) live.putMeta(key, text);
            if (completing) live.putMeta("completed_at", completionTime);
            live.exec("COMMIT", "committing");
        } catch (...) {
            live.writing = false;
            // A failed COMMIT may or may not have rolled back by itself; make sure it did,
            // so the file holds exactly what it held before.
            if (!sqlite3_get_autocommit(live.db.get()))
                sqlite3_exec(live.db.get(), "ROLLBACK", nullptr, nullptr, nullptr);
            try {
                throw;
            } catch (const LockBusy&) {
                return false;
            } catch (const SessionError& e) {
                rescueAfterError(e.what());
                return true;
            }
        }
        live.writing = false;
        heldAreWritten(completionTime);
        // A commit only appends to the -wal: the file changed meanwhile was changed by another
        // program, and the checkpoint must not write into what it put there.
        if (checkUntouched(false)) return true;
        // Fold the log into the main file at once (PASSIVE: never waits for a reader). The
        // -wal then holds no commit the file lacks, so a -wal deleted or damaged later loses
        // nothing written before.
        const bool folded = fold() == Fold::Done;
        stampFiles();
        // What happened to the file during the fsyncs is stamped afresh above: read it back.
        DiskCheck check(live.path, folded);
        check.metaEntry("header_checksum", headerChecksumText());
        const auto commits = static_cast<std::int64_t>(written.commits());
        check.lastCommit(commits);
        if (commits > 0) check.commit(commits, lastWritten);
        if (!check.seen().empty()) notAsWritten(check.seen(), true);
        return true;
    }

    // A write failed with an error other than another program's lock. What the file holds
    // decides what it was: another program's doing, or the disk's (full, failing). Either way
    // every commit is saved again, beside the file; if even that cannot be written, the
    // write's own error ends the session.
    void rescueAfterError(const std::string& error) {
        // Only the file: a failed transaction may have left frames of its own in the -wal.
        if (checkUntouched(false)) return;
        const std::string failure = live.failure;
        DiskCheck check(live.path, false);
        check.metaEntry("header_checksum", headerChecksumText());
        check.lastCommit(static_cast<std::int64_t>(written.commits()));
        if (!check.seen().empty()) return notAsWritten(check.seen() + "; writing failed: " + failure, true);
        try {
            rescue("write_failed", "writing the session file " + live.path + " failed (" + failure + ")", false, true);
        } catch (const SessionError&) {
            throw SessionError(error);
        }
    }

    // The file at the name no longer holds what this writer wrote (DiskCheck saw `seen`).
    void notAsWritten(const std::string& seen, bool goOn) {
        const auto file = stampOf(live.path, true);
        if (!file || !ownFile || !file->sameFile(*ownFile))
            rescue("file_replaced", "the session file " + live.path + " was deleted or replaced by another program",
                   false, goOn);
        else
            rescue(
                "file_overwritten",
                "the session file " + live.path + " was overwritten in place by another program (seen: " + seen + ")",
                false, goOn);
    }

    void stampFiles() {
        fileStamp = stampOf(live.path, true);
        walStamp = stampOf(live.path + "-wal", false);
    }

    // Another program may delete, replace or overwrite the session file or its -wal while
    // we write: a cleanup script, a sync tool, an old copy put back, `cp` over it, a
    // truncation. SQLite would go on writing, into nameless files or over whatever is there,
    // and everything would be lost at the next kill (or at once: "database disk image is
    // malformed"). Only this writer changes the two files, so before each write they must be
    // as it left them; if not, the session is written again whole (rescue()), the supervisor
    // told and the session flagged. True when it was. `walToo`: the -wal too (not right after
    // a commit, which changed it).
    bool checkUntouched(bool walToo) {
        const auto file = stampOf(live.path, true);
        const auto wal = stampOf(live.path + "-wal", false);
        if (file && fileStamp && *file == *fileStamp && (!walToo || !walStamp || (wal && *wal == *walStamp)))
            return false;
        const std::string name = live.path;
        if (!file || !fileStamp || !file->sameFile(*fileStamp))
            rescue("file_replaced", "the session file " + name + " was deleted or replaced by another program", false);
        else if (!(*file == *fileStamp))
            rescue("file_overwritten",
                   "the session file " + name +
                       " was overwritten in place by another program (seen: " + file->changeFrom(*fileStamp) + ")",
                   false);
        else
            rescue("wal_replaced", "the log " + name + "-wal was deleted, replaced or changed by another program",
                   true);
        return true;
    }

    // Writes the whole session again from what this writer wrote and holds, and goes on
    // there (`goOn`; otherwise it is written as a finished session is, one file). `replaceName`:
    // the name still holds this session's own file (only its -wal was touched), which the new
    // file replaces; otherwise the new file takes the name if that is free, else goes beside
    // it as <name>-rescued.warplab-session, leaving what another program put there alone.
    void rescue(const std::string& flagName, const std::string& what, bool replaceName, bool goOn = true) {
        // Our -wal and -shm must not stay beside whatever the name now holds: SQLite would
        // take them for its own. Closed without a checkpoint, which would write our log into
        // that file.
        if (live.db) sqlite3_db_config(live.db.get(), SQLITE_DBCONFIG_NO_CKPT_ON_CLOSE, 1, nullptr);
        live.close();
        // Beside our own file anything there is ours or must go; beside another program's
        // file only what is still ours goes.
        const auto wal = stampOf(live.path + "-wal", false);
        if (replaceName || (wal && walStamp && wal->sameFile(*walStamp))) {
            std::error_code ec;
            fs::remove(live.path + "-wal", ec);
            fs::remove(live.path + "-shm", ec);
        }
        std::string target = live.path;
        if (!replaceName)
            for (int n = 1; anyExists(target); ++n)
                target = (fs::path(resultsDir) / stem).string() + "-rescued" + (n > 1 ? "-" + std::to_string(n) : "") +
                    kExtension;
        const std::string text = what + "; every commit up to then is saved in " + target;
        heldFlags[kFlagPrefix + flagName] = text;
        if (completing) completedAt = utcNow();
        const std::string temp = hiddenPath(kRescuing);
        try {
            buildFile(temp, goOn);
            if (replaceName ? ::rename(temp.c_str(), target.c_str()) != 0 : ::link(temp.c_str(), target.c_str()) != 0)
                throw SessionError("Cannot save the session again as " + target + " (" + what +
                                   "): " + std::strerror(errno) + ".");
            syncFolder(resultsDir);
        } catch (...) {
            removeSessionFiles(temp);
            throw;
        }
        removeSessionFiles(temp);
        heldAreWritten(completedAt);
        if (target != name && movedAway.empty()) movedAway = what;
        live.path = target;
        if (goOn) openForWriting();
        notices.push_back(text);
    }

    static void checkFollows(const std::optional<std::int64_t>& last, std::int64_t frame, const char* caller) {
        if (last && frame <= *last)
            throw std::invalid_argument(std::string("SessionWriter::") + caller + ": frame " + std::to_string(frame) +
                                        " does not follow frame " + std::to_string(*last) + ".");
    }

    template <typename R>
    static void checkJson(const Table<R>& table, const R& r, const char* caller) {
        for (const Field<R>& field : table.fields) {
            if (field.storage != Storage::JsonObject) continue;
            const std::string& text = r.*std::get<std::string R::*>(field.member);
            if (!isJsonObjectOrEmpty(text))
                throw std::invalid_argument(std::string("SessionWriter::") + caller + ": " + field.column +
                                            " must be a JSON object or empty, not '" + text.substr(0, 80) + "'.");
        }
    }

    void checkOpen(const char* caller) const {
        if (finished)
            throw std::logic_error(std::string("SessionWriter::") + caller +
                                   ": the session is already finished or closed.");
    }

    // Retries writeHeld() until it gets the lock, telling `waiting` about once a second.
    void waitForWrite(const WaitCallback& waiting) {
        const auto start = Clock::now();
        auto nextCall = start + std::chrono::seconds(1);
        while (!writeHeld()) {
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
            if (waiting && Clock::now() >= nextCall) {
                waiting(std::chrono::duration<double>(Clock::now() - start).count(), WaitingFor::WriteLock);
                nextCall += std::chrono::seconds(1);
            }
        }
    }

    // Copies the -wal's frames into the file. Done: every frame of the log is in it.
    // HeldByReader: SQLite copied, without an error, only what no reader's snapshot still
    // needs: a program reading in a transaction since before the last commits holds those
    // back (or is checkpointing itself: busy). Failed: SQLite could not copy them (the file
    // is no longer what it wrote, or the disk failed), which no reader is to blame for.
    enum class Fold { Done, HeldByReader, Failed };
    Fold fold() {
        int logFrames = -1, copied = -1;
        const int rc =
            sqlite3_wal_checkpoint_v2(live.db.get(), nullptr, SQLITE_CHECKPOINT_PASSIVE, &logFrames, &copied);
        if (rc == SQLITE_OK) return copied == logFrames ? Fold::Done : Fold::HeldByReader;
        return isBusy(rc) ? Fold::HeldByReader : Fold::Failed;
    }

    // The session's end (finish() or close()): the whole file read back and compared with
    // every commit, flag and the completion this writer wrote. Whatever differs, every commit
    // is saved again beside it. And the run must not end as if all were well when its session
    // is no longer under the name it announced: throws SessionError saying what happened and
    // where the whole session is.
    void verifyAtClose() {
        std::error_code ec;
        DiskCheck check(live.path, !fs::exists(live.path + "-wal", ec));
        check.metaExactly(metaWritten());
        check.lastCommit(static_cast<std::int64_t>(written.commits()));
        std::int64_t id = 0;
        written.forEach([&](const CommitRows& c) { check.commit(++id, c); });
        check.rowCounts(inputRows, frameRows, eventRows);
        if (!check.seen().empty()) notAsWritten(check.seen(), false);
        if (movedAway.empty()) return;
        std::string sentence = movedAway + "; the whole session is saved in " + live.path + ".";
        sentence[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(sentence[0])));
        throw SessionError(sentence);
    }

    // finish() when a reader holds the last commits in the -wal: the whole session, written
    // again in rollback-journal mode, takes the name (rename(2) is atomic: the name always
    // means a whole file). The reader keeps the file it opened; the old -wal and -shm go
    // with it. A kill between the rename and their removal leaves a finished file beside a
    // stale -wal, which readSession recognises and reads without.
    void replaceWithWholeFile() {
        const std::string temp = hiddenPath(kFinishing);
        try {
            buildFile(temp, false);
            if (::rename(temp.c_str(), live.path.c_str()) != 0)
                throw SessionError("Cannot write the finished session " + live.path + ": " + std::strerror(errno) +
                                   ".");
            syncFolder(resultsDir);
        } catch (...) {
            removeSessionFiles(temp);
            throw;
        }
        sqlite3_db_config(live.db.get(), SQLITE_DBCONFIG_NO_CKPT_ON_CLOSE, 1, nullptr);
        live.close();
        std::error_code ec;
        fs::remove(live.path + "-wal", ec);
        fs::remove(live.path + "-shm", ec);
    }
};

SessionWriter::SessionWriter(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
SessionWriter::SessionWriter(SessionWriter&&) noexcept = default;
SessionWriter& SessionWriter::operator=(SessionWriter&&) noexcept = default;

SessionWriter::~SessionWriter() = default;

SessionWriter::Impl& SessionWriter::impl(const char* caller) const {
    if (!impl_) throw std::logic_error(std::string("SessionWriter::") + caller + ": this writer was moved from.");
    return *impl_;
}

const std::string& SessionWriter::path() const { return impl("path").live.path; }

SessionWriter SessionWriter::create(const std::string& resultsDir, const SessionHeader& header,
                                    const FirstCommit& first) {
    if (header.formatVersion != kSessionFormatVersion)
        throw std::invalid_argument("SessionWriter::create: header.formatVersion is " +
                                    std::to_string(header.formatVersion) + " but this warplab writes format version " +
                                    std::to_string(kSessionFormatVersion) + ".");

    // Everything that can be checked is checked before the first file exists, so a bad
    // results folder leaves no litter behind.
    checkResultsFolder(resultsDir);

    auto impl = std::make_unique<Impl>();
    impl->resultsDir = resultsDir;
    impl->header = header;
    SessionHeader& h = impl->header;
    if (h.startedAt.empty()) h.startedAt = utcNow();
    h.sessionId = newSessionId();
    impl->lastChecksum = headerChecksum(h);
    impl->stem = safeName(h.participant, kMaxNameBytes);
    if (impl->stem.empty()) impl->stem = "participant";
    const std::string when = timeForName(h.startedAt);
    if (!when.empty()) impl->stem += "_" + when;
    if (!first.inputs.empty() || !first.frames.empty() || !first.events.empty()) {
        // Added as any rows are, with their checks, and held: buildFile writes them.
        SessionWriter adding(std::move(impl));
        for (const InputRecord& r : first.inputs) adding.addInput(r);
        for (const FrameRecord& r : first.frames) adding.addFrame(r);
        for (const EventRecord& r : first.events) adding.addEvent(r);
        impl = std::move(adding.impl_);
        impl->commitAdded();
    }

    // The header is written into a hidden file beside the session and only then linked to the
    // session's name: a kill at any instant leaves either no session or a readable one with its
    // header, never an empty file. link(2) refuses an existing name, so "pick a free name" and
    // "create it" stay one step (two rigs sharing a results folder never share a file).
    const std::string temp = impl->hiddenPath(kCreating);
    removeAbandonedCreations(resultsDir);  // those of killed runs that are gone
    try {
        try {
            impl->buildFile(temp, true);
        } catch (const SessionError& e) {
            // The first file written in the folder: a failure here is the folder's (a
            // read-only mount, an ACL, a full disk), so say which folder.
            throw SessionError("Results folder '" + resultsDir + "' cannot be written: " + e.what());
        }
        for (int n = 1;; ++n) {
            const std::string name = impl->stem + (n > 1 ? "-" + std::to_string(n) : "") + kExtension;
            const std::string candidate = (fs::path(resultsDir) / name).string();
            if (anyExists(candidate)) continue;
            if (::link(temp.c_str(), candidate.c_str()) == 0) {
                impl->live.path = impl->name = candidate;
                break;
            }
            if (errno != EEXIST || n >= 10000)
                throw SessionError("Cannot create session file " + candidate + ": " + std::strerror(errno) + ".");
        }
        removeSessionFiles(temp);  // the other name stays
        impl->heldAreWritten(impl->completedAt);  // the first commit, if any, is in the file
        impl->openForWriting();
    } catch (...) {
        const std::string path = impl->live.path;
        impl.reset();
        removeSessionFiles(temp);
        if (!path.empty()) removeSessionFiles(path);
        throw;
    }
    return SessionWriter(std::move(impl));
}

void SessionWriter::addInput(const InputRecord& r) {
    Impl& w = impl("addInput");
    w.checkOpen("addInput");
    w.checkFollows(w.lastInputFrame, r.frame, "addInput");
    w.adding.inputs.push_back(r);
    w.lastInputFrame = r.frame;
    hashRow(w.addingChecksum.input, inputTable(), r);
}

void SessionWriter::addFrame(const FrameRecord& r) {
    Impl& w = impl("addFrame");
    w.checkOpen("addFrame");
    w.checkFollows(w.lastFrameFrame, r.frame, "addFrame");
    w.checkJson(frameTable(), r, "addFrame");
    w.adding.frames.push_back(r);
    w.lastFrameFrame = r.frame;
    hashRow(w.addingChecksum.frames, frameTable(), r);
}

void SessionWriter::addEvent(const EventRecord& r) {
    Impl& w = impl("addEvent");
    w.checkOpen("addEvent");
    w.checkJson(eventTable(), r, "addEvent");
    w.adding.events.push_back(r);
    hashRow(w.addingChecksum.events, eventTable(), r);
}

bool SessionWriter::commit() {
    Impl& w = impl("commit");
    w.checkOpen("commit");
    w.commitAdded();
    return w.writeHeld();
}

std::size_t SessionWriter::heldCommits() const { return impl("heldCommits").held.size(); }

double SessionWriter::heldForSeconds() const {
    const Impl& w = impl("heldForSeconds");
    return w.heldSince ? std::chrono::duration<double>(Impl::Clock::now() - *w.heldSince).count() : 0.0;
}

std::vector<std::string> SessionWriter::takeNotices() { return std::exchange(impl("takeNotices").notices, {}); }

void SessionWriter::flag(const std::string& name, const std::string& text) {
    Impl& w = impl("flag");
    w.checkOpen("flag");
    w.addingFlags[kFlagPrefix + name] = text;
}

void SessionWriter::summarize(const std::string& name, const std::string& text) {
    Impl& w = impl("summarize");
    w.checkOpen("summarize");
    w.addingFlags[kSummaryPrefix + name] = text;
}

void SessionWriter::finish(const WaitCallback& waiting, double foldWaitS) {
    Impl& w = impl("finish");
    w.checkOpen("finish");
    w.commitAdded();
    w.completing = true;
    w.waitForWrite(waiting);
    w.finished = true;
    // A finished session becomes one self-contained file, so it can be copied, archived or
    // read from read-only media: every commit folded into it before the run says it is done.
    // A reader's transaction holds the fold back; after foldWaitS the session is written
    // again whole instead.
    // A fold that fails is not a reader's doing: the check below finds what it was.
    const auto start = Impl::Clock::now();
    auto nextCall = start + std::chrono::seconds(1);
    while (w.live.db && w.fold() == Impl::Fold::HeldByReader) {
        if (std::chrono::duration<double>(Impl::Clock::now() - start).count() >= foldWaitS) {
            w.replaceWithWholeFile();
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        if (waiting && Impl::Clock::now() >= nextCall) {
            waiting(std::chrono::duration<double>(Impl::Clock::now() - start).count(), WaitingFor::Readers);
            nextCall += std::chrono::seconds(1);
        }
    }
    // The -wal, now redundant, goes where no other program has the file open (a reader that
    // does keeps WAL mode, which is just as valid: the file alone is whole).
    if (w.live.db) sqlite3_exec(w.live.db.get(), "PRAGMA journal_mode=DELETE", nullptr, nullptr, nullptr);
    w.verifyAtClose();
}

void SessionWriter::close(const WaitCallback& waiting) {
    Impl& w = impl("close");
    w.checkOpen("close");
    w.commitAdded();
    w.waitForWrite(waiting);
    w.finished = true;
    w.verifyAtClose();
}

}  // namespace warplab::session
