#pragma once

#include <stdexcept>
#include <string>

namespace streak {

// Error is what streak throws for bad input: an unknown name, a bad number, a file that cannot
// be read or written, arrays of the wrong size. Its message is one line that names the problem
// (and the file or field), the line the command line prints before exiting with code 2.
class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace streak
