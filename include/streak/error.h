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

// RenderFailure is an Error the input did not cause: the machine could not make the render (no
// OpenGL context, a driver, shader or Embree failure, an image that could not be written once
// its path was accepted). The command line exits with code 1 on it, 2 on any other Error, so a
// farm manager can retry a failure elsewhere and not retry bad input.
class RenderFailure : public Error {
public:
    explicit RenderFailure(const std::string& message) : Error(message) {}
};

// Cancelled is thrown by a render whose cancel callback said stop (api::Renderer::render): no
// image is made. A client that asked for it (Blender's Esc) need not report it as a failure.
class Cancelled : public Error {
public:
    explicit Cancelled(const std::string& message = "the render was cancelled") : Error(message) {}
};

}  // namespace streak
