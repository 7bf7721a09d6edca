// Reading a stored event's detail_json for export (Study::results), for the games' modules: the
// games write their details with nlohmann::json and read them back the same way.
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "game/results.h"

namespace warplab::game {

class EventDetail {
public:
    // "" or text that is not a JSON object reads as an empty detail.
    explicit EventDetail(const std::string& text) {
        if (!text.empty()) json_ = nlohmann::json::parse(text, nullptr, false);
        if (!json_.is_object()) json_ = nlohmann::json::object();
    }
    // kNotApplicable when absent, null (a NaN was stored) or not a number.
    double number(const char* key) const {
        const auto it = json_.find(key);
        return it != json_.end() && it->is_number() ? it->get<double>() : kNotApplicable;
    }
    std::int64_t integer(const char* key, std::int64_t fallback) const {
        const auto it = json_.find(key);
        return it != json_.end() && it->is_number_integer() ? it->get<std::int64_t>() : fallback;
    }
    bool boolean(const char* key, bool fallback) const {
        const auto it = json_.find(key);
        return it != json_.end() && it->is_boolean() ? it->get<bool>() : fallback;
    }
    std::string text(const char* key, const std::string& fallback = "") const {
        const auto it = json_.find(key);
        return it != json_.end() && it->is_string() ? it->get<std::string>() : fallback;
    }

private:
    nlohmann::json json_;
};

}  // namespace warplab::game
