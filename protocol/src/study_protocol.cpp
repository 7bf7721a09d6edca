#include "protocol/study_protocol.h"

#include <algorithm>

#include "protocol/fields.h"

namespace warplab::protocol {

std::string readProtocolFile(const std::string& path) { return strict::readFile(fields::protocolSource(path)); }

std::string protocolGame(const std::string& jsonText, const std::string& sourceName) {
    const fields::Reader r(sourceName);
    return r.game(r.parseObject(jsonText));
}

bool hasGameFields(const std::string& jsonText) {
    const fields::Json document = fields::Json::parse(jsonText, nullptr, false);
    if (!document.is_object()) return false;
    for (const auto& item : document.items()) {
        const std::string& key = item.key();
        if (key == fields::kConditionsKey) continue;
        if (std::none_of(fields::kHeaderKeys.begin(), fields::kHeaderKeys.end(),
                         [&](const char* shared) { return key == shared; }))
            return true;
    }
    return false;
}

std::string withList(const std::string& jsonText, const char* section, const char* key,
                     const std::vector<std::string>& list) {
    fields::Json document = fields::Json::parse(jsonText);
    document[section][key] = list;
    return document.dump(2, ' ', false, fields::Json::error_handler_t::replace) + "\n";
}

}  // namespace warplab::protocol
