#pragma once

#include <string>

namespace streak {

// A frame pattern's path for one frame: its %d or %0Nd (`out_%04d.png`, `fluid_%04d.ply`)
// replaced by the frame number, %% by a %. hasNumber says whether the pattern has one; without,
// the pattern is the one path. Throws Error for another conversion or more than one number.
std::string framePatternPath(const std::string& pattern, long frame, bool& hasNumber);

}  // namespace streak
