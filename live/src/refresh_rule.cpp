#include "refresh_rule.h"

#include <cmath>
#include <sstream>

namespace warplab::live {

bool refreshMismatch(double reportedHz, double protocolHz) {
    // Half a hertz: 59.94 Hz is a 60 Hz display; 50 and 75 Hz are not.
    return !(reportedHz > 0.0) || std::abs(reportedHz - protocolHz) >= 0.5;
}

bool refusesRefresh(double reportedHz, const game::Study& study, bool allowMismatch) {
    return refreshMismatch(reportedHz, study.refreshHz()) && !allowMismatch && !study.warnsOnRefreshMismatch();
}

std::string refreshText(double reportedHz, double protocolHz, const std::string& protocol, bool refused) {
    std::ostringstream text;
    const long wanted = std::lround(protocolHz);
    if (reportedHz > 0.0)
        text << "the display runs at " << reportedHz << " Hz but protocol '" << protocol << "' needs " << protocolHz
             << " Hz";
    else
        text << "the display reports no refresh rate, so it cannot be checked against the " << protocolHz
             << " Hz that protocol '" << protocol << "' needs";
    if (refused)
        text << "; set the display to " << wanted << " Hz" << (reportedHz > 0.0 ? "" : " on a system that reports it")
             << " (or pass --allow-refresh-mismatch for a pilot)";
    return text.str();
}

}  // namespace warplab::live
