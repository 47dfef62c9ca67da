#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace streak {

// Cryptomatte 1.1 (Friedman & Jones, Psyop): ID mattes as ranked (ID, coverage) pairs per pixel,
// in EXR layers {type}00, {type}01, ... (r: ID of rank 2k, g: its coverage, b and a: rank
// 2k + 1; lower case, as the specification and Blender write them), with metadata naming the
// hash and a manifest of every name.

// MurmurHash3_x86_32 (Austin Appleby's, public domain), the hash the specification names.
std::uint32_t murmurHash3(std::string_view bytes, std::uint32_t seed = 0);

// A name's ID: its hash's bits as a float, the exponent clamped to [1, 254] so it is never a
// denormal, an infinity or a NaN ("uint32_to_float32").
float cryptomatteId(std::string_view name);

// The eight hex digits of an ID's float bits, as the manifest writes it.
std::string cryptomatteHex(float id);

// The metadata key of a Cryptomatte type: the first seven hex digits of its name's hash, so it
// stays the same from frame to frame.
std::string cryptomatteKey(std::string_view typeName);

// The manifest: a JSON object from each name to its ID's hex digits.
std::string cryptomatteManifest(const std::vector<std::string>& names);

// The names of a manifest (a JSON object from name to hex ID); none when it is not one.
std::vector<std::string> cryptomatteManifestNames(const std::string& manifest);

// The layers that hold `ranks` (ID, coverage) pairs: ceil(ranks / 2) of them.
int cryptomatteLayers(int ranks);

// The channel of rank r's ID (isCoverage false) or coverage in type `typeName`'s layers:
// "{typeName}{r / 2:02}.{r|g|b|a}".
std::string cryptomatteChannel(std::string_view typeName, int rank, bool isCoverage);

}  // namespace streak
