// A small command-line parser: each subcommand declares its options; anything else is a
// usage error naming the offending argument. Kept in-house because the project needs only
// "--name value", "--flag" and "--name [value]" forms plus generated --help text.
#pragma once

#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "scene/usage_error.h"  // UsageError: a wrong command line, exit status 2

namespace warplab::app {

struct OptionSpec {
    std::string name;  // without the leading "--"
    // Empty for a flag; in brackets ("[SESSION]") for a value that may be left out: the next
    // argument is taken only when it does not start with "-".
    std::string valueName;
    std::string help;
    std::string defaultValue;  // shown in --help; empty = none
};

struct CommandSpec {
    std::string name;
    std::string summary;
    std::string usage;  // e.g. "warplab render [options]"
    std::vector<OptionSpec> options;
    bool allowPositional = false;
};

class ParsedArgs {
public:
    bool has(const std::string& name) const { return values_.count(name) != 0; }
    bool flag(const std::string& name) const { return has(name); }
    std::string string(const std::string& name, const std::string& fallback = "") const;
    // A finite number written whole: "12abc", " 5", "" and "1e999" are a UsageError naming the option.
    double number(const std::string& name, double fallback) const;
    // As number(), and within [min, max]: otherwise a UsageError naming the option, the range
    // and the value as typed.
    double number(const std::string& name, double fallback, double min, double max) const;
    // An integer in [min, max]; UsageError naming the option otherwise.
    long long integer(const std::string& name, long long fallback, long long min, long long max) const;
    // A file path or prefix: empty or blank is a UsageError naming the option, since it would
    // write a file named only by its suffix (or by spaces) into the working directory.
    std::string path(const std::string& name, const std::string& fallback) const;
    const std::vector<std::string>& positional() const { return positional_; }

private:
    friend ParsedArgs parseArgs(const CommandSpec&, const std::vector<std::string>&);
    std::string commandName_;
    std::map<std::string, std::string> values_;
    std::vector<std::string> positional_;
};

// A whole decimal integer: "12abc", "1e3", "" and out-of-range values are a UsageError that
// quotes `what` (e.g. "option --frames needs FIRST:LAST frame numbers") and the text.
long long wholeInteger(const std::string& text, const std::string& what);

// "a,b,c" as {"a", "b", "c"}; an empty item (",", "a,,b", "") is a UsageError that says `what`
// (e.g. "option --ids needs participant ids separated by commas").
std::vector<std::string> commaSeparated(const std::string& text, const std::string& what);

// Parses args (after the subcommand name). "--help" is reported by has("help"). An option
// given twice is a UsageError: which of two values was meant is a guess.
ParsedArgs parseArgs(const CommandSpec& spec, const std::vector<std::string>& args);
std::string helpText(const CommandSpec& spec);

// `text` as one POSIX shell word, single-quoted, for the commands warplab hands to the shell
// (the bench's plot, the demo's analysis).
std::string shellQuoted(const std::string& text);

// Help texts: a number as --help shows it (the shortest form, 0.5 rather than 0.500000), a
// range "low..high" of two such numbers, and a list "a,b,c".
template <class T>
std::string shown(T value) {
    std::ostringstream text;
    text << value;
    return text.str();
}
std::string range(double low, double high);
std::string listed(const std::vector<int>& values);

// Text the user typed, for a one-line message: single-quoted, with line breaks, tabs, other
// control characters, quotes and backslashes escaped (a newline shows as \n), so a message
// that names it stays one line and shows where it went wrong.
std::string quotedForMessage(const std::string& text);
// A list for a one-line message: the first `shown` items, then how many more ("P1, P2, P3, ...
// and 9,997 more"), so that a list of thousands does not become the message.
std::string firstFew(const std::vector<std::string>& items, std::size_t shown = 3);

}  // namespace warplab::app
