// What every game's protocol parser is built from, over the strict reader (strict/json.h) that
// all of warplab's files share, so that all protocol files follow the same rules
// (docs/protocol.md, "Rules"): the header every protocol starts with, its own conditions, condition
// ids, and the field tables below. Public, so that a game's module (games/NAME/) reads its own
// sections with it; nothing here names a game.
#pragma once

#include <cstddef>
#include <functional>
#include <initializer_list>
#include <set>
#include <string>
#include <vector>

#include "condition/condition.h"

#include "protocol/study_protocol.h"
#include "scene/limits.h"
#include "strict/json.h"

namespace warplab::protocol::fields {

using strict::describe;
using strict::elementPath;
using strict::formatNumber;
using strict::joinPath;
using strict::Json;
using strict::kLineLimit;
using strict::kParagraphLimit;
using strict::NumberRange;

// A protocol named `name` (its path, or where its text came from), for the strict reader:
// its refusals are ProtocolErrors.
strict::Source protocolSource(const std::string& name);

// Limits that keep a session's data safe (docs/protocol.md has the reasoning). The session
// writer holds the rows of every frame since the last commit point (end of a trial, a match,
// a phase) in memory and writes them as one transaction, so the longest stretch a game runs
// between two of its commit points, times the refresh, is how many frames a crash can lose
// and how big one commit, and the WAL it goes through, can grow. 300 s at the 1000 Hz ceiling
// is 300000 frames: some 90 MB of rows at the click game's ~300 bytes a frame.
inline constexpr double kRefreshLimitHz = 1000;
inline constexpr double kCommitStretchLimitS = 300;

// The top level every protocol starts with, in the documented order; the game's sections follow.
Json headerJson(int formatVersion, const std::string& name, const std::string& description, const std::string& game);
// The canonical file text: two-space indent, trailing newline. Bytes that are not UTF-8 become
// replacement characters rather than throwing, so storing a session's copy never fails.
std::string canonicalText(const Json& document);

// The strict reader for a protocol: every message starts "protocol 'NAME': ", and the
// protocol's header, conditions and condition ids are read here.
class Reader : public strict::Reader {
public:
    explicit Reader(const std::string& source);

    // The required string "game".
    std::string game(const Json& document) const;
    // "game" must be `expected`. Checked first: in a file for another game nothing else means
    // what this parser thinks, so its other fields are no use in the message.
    void requireGame(const Json& document, const std::string& expected) const;
    // "name", a required line, and "description", optional free text.
    void nameAndDescription(const Json& document, std::string& name, std::string& description) const;

    using strict::Reader::choice;
    // One of EnumNames<E>, spelt exactly; a message lists them with `out`'s value (the field's
    // default, since nothing has set it yet) first.
    template <class E>
    void choice(const Json* parent, const std::string& path, const char* key, E& out) const {
        std::vector<const char*> allowed{nameOf(out)};
        for (const auto& entry : EnumNames<E>::list)
            if (entry.value != out) allowed.push_back(entry.name);
        std::string name;
        choice(parent, path, key, allowed, name);
        for (const auto& entry : EnumNames<E>::list)
            if (name == entry.name) out = entry.value;
    }

    // The top-level "conditions" object (new in format_version `since`): each condition's parts,
    // checked on their own; whether each can run is asked once the refresh is final
    // (requireConditions). A name that is a preset must repeat the preset's parts. Condition ids
    // name conditions; they are checked against these and the presets from here on.
    // Its pacing keys (frame_time_jitter, hitches) are new in format_version `pacingSince`.
    std::vector<condition::Condition> conditions(const Json& document, int formatVersion, int since, int pacingSince);
    // Every defined condition runs at refreshHz: checked before the fields that name them, so
    // the error names the definition's part rather than a field that uses it.
    void requireConditionsRun(double refreshHz) const;
    // ... and is named by some field (requireCondition), checked after them.
    void requireConditionsUsed() const;
    const condition::ConditionTable& conditionTable() const { return conditions_; }

    // Condition ids are only read as strings here; whether they exist and fit the refresh is asked
    // of the condition table once the refresh is final (requireCondition), so defaults are checked too.
    void conditionId(const Json* parent, const std::string& path, const char* key, std::string& out) const;
    // A non-empty array of distinct condition ids.
    void conditionList(const Json* parent, const std::string& path, const char* key,
                       std::vector<std::string>& out) const;
    void requireCondition(const std::string& where, const std::string& id, double refreshHz) const;
    // Each of a list, named path[i].
    void requireConditions(const std::string& path, const std::vector<std::string>& ids, double refreshHz) const;

private:
    // A definition's frame_time_jitter and hitches, at `path`.
    void pacing(const Json& value, const std::string& path, int formatVersion, int since,
                condition::Condition& c) const;
    // A definition's frame_times, at `path`: sets its trace and render rate (frame_times_json.cpp).
    void frameTimes(const Json& value, const std::string& path, condition::Condition& c) const;
    condition::ConditionTable conditions_;
    mutable std::set<std::string> used_;  // the conditions requireCondition was asked about
};

// A condition's "frame_times" as a stored copy keeps it: the frame times inline.
void writeFrameTimes(Json& object, const condition::Condition& c);

// The "conditions" object as a canonical protocol writes it; nothing when there are none.
void writeConditions(Json& document, const std::vector<condition::Condition>& defined);

// ---------------------------------------------------------------- field tables
// Each protocol object's keys are one table (as records.h is for the session's columns): a
// key's name, how it is read and how it is written, each once. The object's known-key list,
// its reading (in table order, which is also the order errors are found in) and toJson all
// walk the table.
template <class P>
struct Key {
    const char* name;
    std::function<void(const Reader&, const Json* object, const std::string& path, P&)> read;
    std::function<void(Json& object, const P&)> write;
    std::function<bool(const P&)> isDefault;
    // The format version that added the key: a file of an older version is written without it
    // unless it differs from the default (which such files meant), and with refusedBefore it
    // may not set it either.
    int newIn = 1;
    bool refusedBefore = false;
    // A key renamed in format_version `renamedIn` is two keys of one member: the old name, read
    // and written by the versions before it and refused from it on (naming `renamedTo`), and the
    // new name, refused before it and never written there (the old name carries the value).
    int renamedIn = 0;  // the old name's: the version from which files use renamedTo instead
    const char* renamedTo = "";
    bool renaming = false;  // the new name's: written only from newIn on

    Key since(int version, bool refused = false) const {
        Key k = *this;
        k.newIn = version;
        k.refusedBefore = refused;
        return k;
    }
    // This key's name until `version`, from which files call it `to` (a key of its own, made
    // with renames(version)).
    Key renamed(int version, const char* to) const {
        Key k = *this;
        k.renamedIn = version;
        k.renamedTo = to;
        return k;
    }
    // The new name of a key renamed in `version`.
    Key renames(int version) const {
        Key k = since(version, true);
        k.renaming = true;
        return k;
    }
    bool existsIn(int formatVersion) const { return renamedIn == 0 || formatVersion < renamedIn; }
    bool writtenIn(int formatVersion, const P& p) const {
        if (!existsIn(formatVersion)) return false;
        if (renaming) return formatVersion >= newIn;
        return formatVersion >= newIn || !isDefault(p);
    }
};

// A top-level object of a protocol (display, test, ...) and its keys.
template <class P>
struct Section {
    const char* name;
    std::vector<Key<P>> keys;
    // The format version from which files no longer have the section (0: every version has it),
    // and the key that holds its data from then on. Older files keep reading it (their sessions
    // replay with what it says), so its keys stay known; a newer file that has it is refused
    // naming the replacement, since read it would be ignored and not read it would be a setting
    // the study silently lost. toJson writes it only for the versions that have it.
    int replacedIn = 0;
    const char* replacedBy = "";

    Section replaced(int version, const char* by) const {
        Section s = *this;
        s.replacedIn = version;
        s.replacedBy = by;
        return s;
    }
    bool existsIn(int formatVersion) const { return replacedIn == 0 || formatVersion < replacedIn; }
};

// The member a key reads and writes: p.*m, or (p.*s).*m for a nested struct. The accessor
// works on const and non-const P alike.
template <class P, class T>
auto at(T P::*m) {
    return [m](auto& p) -> auto& { return p.*m; };
}
template <class P, class S, class T>
auto at(S P::*s, T S::*m) {
    return [ s, m ](auto& p) -> auto& { return (p.*s).*m; };
}

// The keys of the usual kinds, each read with the Reader function of the same name.
template <class P>
struct Keys {
    template <class Get>
    static Key<P> make(const char* name, Get get,
                       std::function<void(const Reader&, const Json*, const std::string&, P&)> read) {
        return {name, std::move(read), [name, get](Json& o, const P& p) { o[name] = get(p); },
                [get](const P& p) {
                    const P defaults{};
                    return get(p) == get(defaults);
                }};
    }
    // A key read and written its own way (an array of objects, of checked lines); there since
    // version 1, so it needs no default to compare with.
    static Key<P> custom(const char* name, std::function<void(const Reader&, const Json*, const std::string&, P&)> read,
                         std::function<void(Json&, const P&)> write) {
        return {name, std::move(read), std::move(write), {}};
    }
    template <class Get>
    static Key<P> number(const char* name, Get get, NumberRange range) {
        return make(name, get, [name, get, range](const Reader& r, const Json* o, const std::string& path, P& p) {
            r.number(o, path, name, range, get(p));
        });
    }
    template <class Get>
    static Key<P> integer(const char* name, Get get, int low, int high) {
        return make(name, get, [name, get, low, high](const Reader& r, const Json* o, const std::string& path, P& p) {
            r.integer(o, path, name, low, high, get(p));
        });
    }
    template <class Get>
    static Key<P> boolean(const char* name, Get get) {
        return make(name, get, [name, get](const Reader& r, const Json* o, const std::string& path, P& p) {
            r.boolean(o, path, name, get(p));
        });
    }
    // An enum with EnumNames, written as its JSON spelling.
    template <class Get>
    static Key<P> choice(const char* name, Get get) {
        Key<P> k = make(name, get, [name, get](const Reader& r, const Json* o, const std::string& path, P& p) {
            r.choice(o, path, name, get(p));
        });
        k.write = [name, get](Json& o, const P& p) { o[name] = nameOf(get(p)); };
        return k;
    }
    template <class Get>
    static Key<P> conditionId(const char* name, Get get) {
        return make(name, get, [name, get](const Reader& r, const Json* o, const std::string& path, P& p) {
            r.conditionId(o, path, name, get(p));
        });
    }
    template <class Get>
    static Key<P> conditionList(const char* name, Get get) {
        return make(name, get, [name, get](const Reader& r, const Json* o, const std::string& path, P& p) {
            r.conditionList(o, path, name, get(p));
        });
    }
};

// A phase's "instructions" (new in format_version `since`): the text of the screen that opens
// the phase, "" for none. Files of older versions have no such screens -- what their sessions
// were recorded with -- so the parser clears them there and such files may not set one. A
// struct of an older version is written without them where it has none (what such files
// mean), and with them where it has some, so that parsing the copy refuses it rather than
// replaying it without its screens.
template <class P, class Get>
Key<P> instructionsKey(Get get, int since) {
    Key<P> k = Keys<P>::make("instructions", get, [get](const Reader& r, const Json* o, const std::string& path, P& p) {
                   r.paragraph(o, path, "instructions", get(p));
               }).since(since, true);
    k.isDefault = [get](const P& p) { return get(p).empty(); };
    return k;
}

// The keys' present names (a renamed key by its new one), in table order.
template <class P>
std::vector<const char*> keyNames(const std::vector<Key<P>>& keys) {
    std::vector<const char*> names;
    for (const Key<P>& k : keys)
        if (k.renamedIn == 0) names.push_back(k.name);
    return names;
}

// The names a file of `formatVersion` may use: a renamed key by the name its version has.
template <class P>
std::vector<const char*> keyNamesIn(const std::vector<Key<P>>& keys, int formatVersion) {
    std::vector<const char*> names;
    for (const Key<P>& k : keys)
        if (k.existsIn(formatVersion) && !(k.renaming && formatVersion < k.newIn)) names.push_back(k.name);
    return names;
}

// The keys every protocol's top level starts with, in the documented order; headerJson
// writes them and the game's sections follow.
inline const std::vector<const char*> kHeaderKeys{"format_version", "name", "description", "game"};
// The protocol's own conditions follow the header (Reader::conditions).
inline constexpr const char* kConditionsKey = "conditions";

// The top level's known keys: the header's, then the sections'.
template <class P>
std::vector<const char*> topLevelKeys(const std::vector<Section<P>>& sections) {
    std::vector<const char*> names = kHeaderKeys;
    names.push_back(kConditionsKey);
    for (const Section<P>& s : sections) names.push_back(s.name);
    return names;
}

// One object's keys read from `object` at `path` (absent keys keep their defaults): a renamed
// key under the name another version gives it first (said so, where it would be unknown), then
// unknown keys, then keys this format version may not have, then each key in table order.
template <class P>
void readKeys(const Reader& r, const Json& object, const std::string& path, const std::vector<Key<P>>& keys,
              int formatVersion, P& out) {
    const auto refuseAsNew = [&](const Key<P>& k) {
        r.fail(joinPath(path, k.name),
               "is new in format_version " + std::to_string(k.newIn) + ", but this file is format_version " +
                   std::to_string(formatVersion));
    };
    for (const Key<P>& k : keys) {
        if (!object.contains(k.name)) continue;
        if (k.renaming && formatVersion < k.newIn) refuseAsNew(k);
        if (!k.existsIn(formatVersion))
            r.fail(joinPath(path, k.name),
                   std::string("was renamed ") + k.renamedTo + " in format_version " + std::to_string(k.renamedIn) +
                       ", and this file is format_version " + std::to_string(formatVersion) + ": use " +
                       joinPath(path, k.renamedTo) + " instead");
    }
    r.requireKnownKeys(object, path, keyNamesIn(keys, formatVersion));
    for (const Key<P>& k : keys)
        if (k.refusedBefore && formatVersion < k.newIn && object.contains(k.name)) refuseAsNew(k);
    for (const Key<P>& k : keys) k.read(r, &object, path, out);
}

template <class P>
void writeKeys(Json& object, const std::vector<Key<P>>& keys, int formatVersion, const P& p) {
    for (const Key<P>& k : keys)
        if (k.writtenIn(formatVersion, p)) k.write(object, p);
}

// The name a file of `formatVersion` gives the key that is now `name` in `keys`: its older name
// in files older than the rename. Messages about a value name the key the file has.
template <class P>
std::string keyNameIn(const std::vector<Key<P>>& keys, const char* name, int formatVersion) {
    for (const Key<P>& k : keys)
        if (k.renamedIn != 0 && std::string(k.renamedTo) == name && formatVersion < k.renamedIn) return k.name;
    return name;
}

// Every section present in `document`, read in table order.
template <class P>
void readSections(const Reader& r, const Json& document, const std::vector<Section<P>>& sections, int formatVersion,
                  P& out) {
    for (const Section<P>& s : sections) {
        if (document.contains(s.name) && !s.existsIn(formatVersion))
            r.fail(s.name,
                   std::string("was replaced by ") + s.replacedBy + " in format_version " +
                       std::to_string(s.replacedIn) + ", and this file is format_version " +
                       std::to_string(formatVersion) + ": use " + s.replacedBy + " instead");
        if (const Json* object = r.object(document, "", s.name))
            readKeys(r, *object, s.name, s.keys, formatVersion, out);
    }
}

// The path ("training.low_mode") a file of `formatVersion` has for the key now at
// section.key.
template <class P>
std::string keyPathIn(const std::vector<Section<P>>& sections, const char* section, const char* key,
                      int formatVersion) {
    for (const Section<P>& s : sections)
        if (std::string(s.name) == section) return joinPath(section, keyNameIn(s.keys, key, formatVersion));
    return joinPath(section, key);
}

template <class P>
void writeSections(Json& document, const std::vector<Section<P>>& sections, int formatVersion, const P& p) {
    for (const Section<P>& s : sections)
        if (s.existsIn(formatVersion)) writeKeys(document[s.name], s.keys, formatVersion, p);
}

// A game's whole protocol as its canonical text: the header, its own conditions, then its
// sections. P has the header's members and a conditionTable.
template <class P>
std::string protocolText(const P& p, const std::vector<Section<P>>& sections) {
    Json document = headerJson(p.formatVersion, p.name, p.description, p.game);
    writeConditions(document, p.conditionTable.defined());
    writeSections(document, sections, p.formatVersion, p);
    return canonicalText(document);
}

// The keys of each element of an array of objects: the array's path ("matches.rounds") and the
// element's keys, in table order.
struct ElementKeys {
    std::string array;
    std::vector<const char*> keys;
};

// Every key as a JSON path ("display.refresh_hz"), header first, in table order (a renamed key
// by its present name, whose row on the page gives the older one); the keys of an
// array's elements ("matches.rounds[].name") follow their section's own keys, as the page
// documents them.
template <class P>
std::vector<std::string> keyPaths(const std::vector<Section<P>>& sections,
                                  const std::vector<ElementKeys>& elements = {}) {
    std::vector<std::string> paths(kHeaderKeys.begin(), kHeaderKeys.end());
    paths.emplace_back(kConditionsKey);
    for (const Section<P>& s : sections) {
        for (const Key<P>& k : s.keys)
            if (k.renamedIn == 0) paths.push_back(joinPath(s.name, k.name));  // a renamed key under its new name
        for (const ElementKeys& e : elements)
            if (e.array.rfind(std::string(s.name) + ".", 0) == 0)
                for (const char* k : e.keys) paths.push_back(e.array + "[]." + k);
    }
    return paths;
}

// display.guard_band and display.supersampling (RenderSettings), alike in every game: new with
// format 2, so older files are written with them only when they are not the defaults.
// display.photon_marker came later, in each game's own format version `photonMarkerSince`;
// older files may not set it (their sessions ran without a marker).
template <class P>
std::vector<Key<P>> renderKeys(int photonMarkerSince) {
    using K = Keys<P>;
    return {
        K::number("guard_band", at(&P::rendering, &RenderSettings::guardBand), {0, false, scene::kMaxGuardBand, false})
            .since(2),
        K::integer("supersampling", at(&P::rendering, &RenderSettings::supersampling), 1, scene::kMaxSupersampling)
            .since(2),
        K::choice("photon_marker", at(&P::rendering, &RenderSettings::photonMarker)).since(photonMarkerSince, true),
        K::number("max_late_share", at(&P::rendering, &RenderSettings::maxLateShare), {0, false, 1, false})
            .since(photonMarkerSince, true)};
}

}  // namespace warplab::protocol::fields
