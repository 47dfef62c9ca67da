#pragma once

#include <span>
#include <string>

namespace streak {

// Writes to a temporary file beside path and renames it over path, so readers never see a
// partial file and a failure leaves nothing behind. Throws std::runtime_error with the reason
// (the caller names the file in its Error).
void writeFileAtomically(const std::string& path, std::span<const char> bytes);

// The reason an errno stands for ("No such file or directory").
std::string errnoReason(int err);

}  // namespace streak
