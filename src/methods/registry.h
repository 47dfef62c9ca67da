#pragma once

#include "methods/renderer.h"
#include "util/options.h"

#include <memory>
#include <span>
#include <string>
#include <string_view>

namespace streak {

// A method streak can render with: its name (for -m), a one-line description, and its factory.
// The factory reads the method's own options (e.g. samples=256) from the map; keys it does not
// ask for are rejected afterwards.
struct MethodInfo {
    std::string_view name;
    std::string_view description;
    std::unique_ptr<Renderer> (*create)(OptionMap& options);
};

// All registered methods, in registration order (src/methods/registry.cpp: one line each).
std::span<const MethodInfo> registeredMethods();

// Creates method `name` with its options; Error for an unknown name (listing the known ones),
// a bad option value or an option the method does not take.
std::unique_ptr<Renderer> createRenderer(std::string_view name, OptionMap options);

}  // namespace streak
