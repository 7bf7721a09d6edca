#include "protocol/study_protocol.h"

#include <algorithm>

#include "protocol/fields.h"

namespace warplab::protocol {

std::string readProtocolFile(const std::string& path) { return strict::readFile(detail::protocolSource(path)); }

std::string protocolGame(const std::string& jsonText, const std::string& sourceName) {
    const detail::Reader r(sourceName);
    return r.game(r.parseObject(jsonText));
}

bool hasGameFields(const std::string& jsonText) {
    const detail::Json document = detail::Json::parse(jsonText, nullptr, false);
    if (!document.is_object()) return false;
    for (const auto& item : document.items()) {
        const std::string& key = item.key();
        if (key == detail::kConditionsKey) continue;
        if (std::none_of(detail::kHeaderKeys.begin(), detail::kHeaderKeys.end(),
                         [&](const char* shared) { return key == shared; }))
            return true;
    }
    return false;
}

}  // namespace warplab::protocol
