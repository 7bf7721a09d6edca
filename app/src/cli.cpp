#include "cli.h"

#include <algorithm>
#include <cerrno>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace warplab::app {
namespace {

// strtod and strtoll skip leading white space; a value that starts with it was not typed as
// meant (a stray quote in a script), so it is refused like trailing junk.
bool startsBlank(const std::string& text) {
    return text.empty() || std::isspace(static_cast<unsigned char>(text[0])) != 0;
}

// A limit as a person writes it: "-36000", "0.5", "1e+06".
std::string limitText(double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.15g", value);
    return buffer;
}

}  // namespace

std::string ParsedArgs::string(const std::string& name, const std::string& fallback) const {
    const auto it = values_.find(name);
    return it == values_.end() ? fallback : it->second;
}

double ParsedArgs::number(const std::string& name, double fallback) const {
    const auto it = values_.find(name);
    if (it == values_.end()) return fallback;
    const char* text = it->second.c_str();
    char* end = nullptr;
    errno = 0;
    const double value = std::strtod(text, &end);
    if (startsBlank(it->second) || end == text || *end != '\0' || errno == ERANGE || !std::isfinite(value))
        throw UsageError("option --" + name + " of 'warplab " + commandName_ + "' needs a number, got '" + it->second +
                         "'");
    return value;
}

double ParsedArgs::number(const std::string& name, double fallback, double min, double max) const {
    const double value = number(name, fallback);
    if (!(value >= min && value <= max))
        throw UsageError("option --" + name + " of 'warplab " + commandName_ + "' must be between " + limitText(min) +
                         " and " + limitText(max) + ", got " + string(name));
    return value;
}

std::string ParsedArgs::path(const std::string& name, const std::string& fallback) const {
    const auto it = values_.find(name);
    if (it == values_.end()) return fallback;
    if (it->second.find_first_not_of(" \t\n\r\v\f") == std::string::npos)
        throw UsageError("option --" + name + " of 'warplab " + commandName_ + "' needs a path, got '" + it->second +
                         "'");
    return it->second;
}

long long ParsedArgs::integer(const std::string& name, long long fallback, long long min, long long max) const {
    const auto it = values_.find(name);
    long long value = fallback;
    if (it != values_.end()) {
        const char* text = it->second.c_str();
        char* end = nullptr;
        errno = 0;
        value = std::strtoll(text, &end, 10);
        // "+5" is refused as a typo would be: a seed or a count is written as its digits.
        if (startsBlank(it->second) || it->second.rfind('+', 0) == 0 || end == text || *end != '\0' || errno == ERANGE)
            throw UsageError("option --" + name + " of 'warplab " + commandName_ + "' needs an integer, got '" +
                             it->second + "'");
    }
    if (value < min || value > max)
        throw UsageError("option --" + name + " of 'warplab " + commandName_ + "' must be between " +
                         std::to_string(min) + " and " + std::to_string(max) + ", got " + std::to_string(value));
    return value;
}

std::vector<std::string> commaSeparated(const std::string& text, const std::string& what) {
    std::vector<std::string> items;
    std::size_t at = 0;
    while (at <= text.size()) {
        const std::size_t comma = std::min(text.find(',', at), text.size());
        items.push_back(text.substr(at, comma - at));
        if (items.back().empty()) throw UsageError(what);
        at = comma + 1;
    }
    return items;
}

long long wholeInteger(const std::string& text, const std::string& what) {
    const char* begin = text.c_str();
    char* end = nullptr;
    errno = 0;
    const long long value = std::strtoll(begin, &end, 10);
    if (startsBlank(text) || text.rfind('+', 0) == 0 || end == begin || *end != '\0' || errno == ERANGE)
        throw UsageError(what + ", got '" + text + "'");
    return value;
}

ParsedArgs parseArgs(const CommandSpec& spec, const std::vector<std::string>& args) {
    ParsedArgs parsed;
    parsed.commandName_ = spec.name;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& arg = args[i];
        if (arg == "--help" || arg == "-h") {
            parsed.values_["help"] = "";
            continue;
        }
        if (arg.rfind("--", 0) != 0 || arg.size() == 2) {
            if (spec.allowPositional && (arg.empty() || arg[0] != '-')) {
                parsed.positional_.push_back(arg);
                continue;
            }
            throw UsageError("unexpected argument '" + arg + "' for 'warplab " + spec.name + "'");
        }
        std::string name = arg.substr(2);
        std::optional<std::string> inlineValue;
        if (const auto eq = name.find('='); eq != std::string::npos) {
            inlineValue = name.substr(eq + 1);
            name = name.substr(0, eq);
        }
        const OptionSpec* option = nullptr;
        for (const auto& o : spec.options)
            if (o.name == name) option = &o;
        if (option == nullptr) throw UsageError("unknown option '--" + name + "' for 'warplab " + spec.name + "'");
        if (parsed.values_.count(name) != 0)
            throw UsageError("option --" + name + " of 'warplab " + spec.name + "' is given more than once");
        if (option->valueName.empty()) {
            if (inlineValue) throw UsageError("option --" + name + " of 'warplab " + spec.name + "' takes no value");
            parsed.values_[name] = "";
        } else if (inlineValue) {
            parsed.values_[name] = *inlineValue;
        } else if (option->valueName.front() == '[') {
            const bool given = i + 1 < args.size() && !args[i + 1].empty() && args[i + 1][0] != '-';
            parsed.values_[name] = given ? args[++i] : "";
        } else {
            if (i + 1 >= args.size())
                throw UsageError("option --" + name + " of 'warplab " + spec.name + "' needs a value (" +
                                 option->valueName + ")");
            parsed.values_[name] = args[++i];
        }
    }
    return parsed;
}

std::string shellQuoted(const std::string& text) {
    std::string quoted = "'";
    for (char ch : text) quoted += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
    return quoted + "'";
}

std::string helpText(const CommandSpec& spec) {
    std::ostringstream out;
    out << "usage: " << spec.usage << "\n\n" << spec.summary << "\n";
    if (!spec.options.empty()) out << "\noptions:\n";
    for (const auto& o : spec.options) {
        std::string left = "  --" + o.name + (o.valueName.empty() ? "" : " " + o.valueName);
        if (left.size() < 26)
            left.resize(26, ' ');
        else
            left += "\n" + std::string(26, ' ');
        out << left << o.help;
        if (!o.defaultValue.empty()) out << " (default " << o.defaultValue << ")";
        out << "\n";
    }
    out << "  --help                  show this text\n";
    return out.str();
}

std::string range(double low, double high) { return shown(low) + ".." + shown(high); }

std::string listed(const std::vector<int>& values) {
    std::string text;
    for (const int v : values) text += (text.empty() ? "" : ",") + std::to_string(v);
    return text;
}

std::string quotedForMessage(const std::string& text) {
    std::string quoted = "'";
    for (const char ch : text) {
        const auto byte = static_cast<unsigned char>(ch);
        if (ch == '\n')
            quoted += "\\n";
        else if (ch == '\t')
            quoted += "\\t";
        else if (ch == '\r')
            quoted += "\\r";
        else if (ch == '\'' || ch == '\\')
            quoted += std::string("\\") + ch;
        else if (byte < 0x20 || byte == 0x7f) {
            char hex[8];
            std::snprintf(hex, sizeof hex, "\\x%02x", byte);
            quoted += hex;
        } else {
            quoted += ch;
        }
    }
    return quoted + "'";
}

std::string firstFew(const std::vector<std::string>& items, std::size_t shown) {
    std::string text;
    for (std::size_t i = 0; i < items.size() && i < shown; ++i) text += (i == 0 ? "" : ", ") + items[i];
    if (items.size() <= shown) return text;
    // 9997 -> "9,997": a count a reader takes in at a glance.
    std::string more = std::to_string(items.size() - shown);
    for (auto at = static_cast<std::ptrdiff_t>(more.size()) - 3; at > 0; at -= 3)
        more.insert(static_cast<std::size_t>(at), ",");
    return text + ", ... and " + more + " more";
}

}  // namespace warplab::app
