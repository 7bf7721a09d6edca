// Private to session/: what the reader needs to read files of older format versions as today's
// records: the input columns of versions 1 to 4, and version 1's frame and event rows.
#pragma once

#include "session/records.h"
#include "session/session_store.h"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace warplab::session::detail {

// ---- versions 1 to 4, read only: the input table ----
// Frozen as versions 1 to 4 wrote it, before version 5 added `text`: the column order is also
// the order their checksums were computed in. Read into today's InputRecord, whose text stays "".
inline const std::vector<Field<InputRecord>>& v1To4InputFields() {
    using R = InputRecord;
    static const std::vector<Field<R>> fields = {
        {"frame", &R::frame},      {"display_time", &R::displayTime}, {"mouse_dx", &R::mouseDx},
        {"mouse_dy", &R::mouseDy}, {"buttons", &R::buttons},          {"keys", &R::keys},
    };
    return fields;
}

// ---- version 1, read only: the frames and events tables ----
// Frozen as version 1 wrote them: the column order is also the order its checksums were
// computed in. A version-1 row type extends today's record with the columns version 2 moved
// into detail_json; toRecord() below folds them in.

struct V1FrameRow : FrameRecord {
    double targetX = 0, targetY = 0, targetZ = 0;
    std::int64_t targetVisible = 0;
};
struct V1EventRow : EventRecord {
    int difficulty = 0;
    double targetSpeed = 0, spawnTime = 0, aimTime = 0, angularErrorDeg = 0;
};

inline const std::vector<Field<V1FrameRow>>& v1FrameFields() {
    using R = V1FrameRow;
    static const std::vector<Field<R>> fields = {
        {"frame", &R::frame},
        {"mode", &R::condition},
        {"kind", &R::kind},
        {"frame_ms", &R::frameMs},
        {"missed_vsyncs", &R::missedVsyncs},
        {"camera_yaw", &R::cameraYaw},
        {"camera_pitch", &R::cameraPitch},
        {"target_x", &R::targetX},
        {"target_y", &R::targetY},
        {"target_z", &R::targetZ},
        {"target_visible", &R::targetVisible},
    };
    return fields;
}
inline const std::vector<Field<V1EventRow>>& v1EventFields() {
    using R = V1EventRow;
    static const std::vector<Field<R>> fields = {
        {"frame", &R::frame},
        {"type", &R::type},
        {"phase", &R::phase},
        {"trial", &R::trial},
        {"mode", &R::condition},
        {"difficulty", &R::difficulty},
        {"target_speed", &R::targetSpeed},
        {"spawn_time", &R::spawnTime},
        {"event_time", &R::eventTime},
        {"aim_time", &R::aimTime},
        {"world_outcome", &R::worldOutcome},
        {"displayed_outcome", &R::displayedOutcome},
        {"angular_error_deg", &R::angularErrorDeg},
        {"detail_json", &R::detailJson, /*jsonObject=*/true},
    };
    return fields;
}

// Rows the storage-class checks pass but that are still not what the writer wrote.
template <typename Row>
bool rowValid(const Row&) {
    return true;
}
inline bool rowValid(const V1FrameRow& r) { return r.targetVisible == 0 || r.targetVisible == 1; }
inline bool rowValid(const V1EventRow& r) { return isJsonObjectOrEmpty(r.detailJson); }

// Rows as records of today's format. Version 1's shooter columns go into detail_json under the
// keys the shooter writes today (docs/session-format.md, "Version 1"), so the session replays.
template <typename Record>
Record toRecord(Record r) {
    return r;
}
inline FrameRecord toRecord(V1FrameRow&& r) {
    FrameRecord out = std::move(static_cast<FrameRecord&>(r));
    out.detailJson = r.targetVisible
        ? nlohmann::json{{"target", nlohmann::json::array({r.targetX, r.targetY, r.targetZ})}}.dump()
        : std::string();
    return out;
}
inline EventRecord toRecord(V1EventRow&& r) {
    nlohmann::json detail = r.detailJson.empty() ? nlohmann::json::object() : nlohmann::json::parse(r.detailJson);
    detail["difficulty"] = r.difficulty;
    if (r.type == "shot" || r.type == "timeout" || r.type == "level") detail["target_speed"] = r.targetSpeed;
    if (r.type == "shot" || r.type == "timeout") {
        detail["spawn_time"] = r.spawnTime;
        detail["aim_time"] = r.aimTime;
        detail["angular_error_deg"] = r.angularErrorDeg;
    }
    EventRecord out = std::move(static_cast<EventRecord&>(r));
    out.detailJson = detail.dump();
    return out;
}

}  // namespace warplab::session::detail
