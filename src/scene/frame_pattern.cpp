#include "scene/frame_pattern.h"

#include "util/error.h"

#include <cctype>
#include <cstdio>

namespace streak {

std::string framePatternPath(const std::string& pattern, long frame, bool& hasNumber) {
    std::string out;
    int conversions = 0;
    for (std::size_t i = 0; i < pattern.size(); ++i) {
        if (pattern[i] != '%') {
            out += pattern[i];
            continue;
        }
        if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
            out += '%', ++i;
            continue;
        }
        std::size_t j = i + 1;
        while (j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j]))) ++j;
        const std::string width = pattern.substr(i + 1, j - i - 1);
        if (j >= pattern.size() || pattern[j] != 'd' || width.size() > 2 || (!width.empty() && width[0] != '0'))
            throw Error("'" + pattern + "': the only conversion a frame pattern takes is %d or %0Nd (write %% for a %)");
        char number[32];
        std::snprintf(number, sizeof number, ("%" + width + "ld").c_str(), frame);
        out += number;
        ++conversions;
        i = j;
    }
    if (conversions > 1) throw Error("'" + pattern + "' has more than one %d");
    hasNumber = conversions == 1;
    return out;
}

}  // namespace streak
