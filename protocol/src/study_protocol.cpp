#include "protocol/study_protocol.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "json_fields.h"

namespace warplab::protocol {

std::string readProtocolFile(const std::string& path) {
    const std::string prefix = "protocol '" + path + "': ";
    std::error_code error;
    const auto status = std::filesystem::status(path, error);
    if (!std::filesystem::exists(status)) throw ProtocolError(prefix + "no such file");
    if (std::filesystem::is_directory(status)) throw ProtocolError(prefix + "is a directory, not a file");
    // A pipe or a device would block or never end.
    if (!std::filesystem::is_regular_file(status)) throw ProtocolError(prefix + "is not a regular file");
    const auto size = std::filesystem::file_size(path, error);
    if (!error && size > detail::kMaxProtocolBytes)
        throw ProtocolError(prefix + "is " + std::to_string(size) + " bytes, more than a protocol may be (" +
                            std::to_string(detail::kMaxProtocolBytes) + ")");
    std::ifstream file(path, std::ios::binary);
    if (!file) throw ProtocolError(prefix + "cannot be opened for reading");
    std::ostringstream text;
    text << file.rdbuf();
    if (file.bad()) throw ProtocolError(prefix + "cannot be read");
    return text.str();
}

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
