#pragma once

#include <stdexcept>
#include <string>

namespace streak {

// Error is what streak throws for bad input: an unknown name, a bad number, a file that cannot
// be read or written. Its message is one line that names the problem (and the file or field).
// Only the command line turns it into stderr output and exit code 2; library code never exits.
class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace streak
