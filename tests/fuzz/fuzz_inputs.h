#pragma once

// What the fuzz targets and write_seeds (their seeds and dictionaries) agree on: the input
// format of method_options_fuzz, the scenes it renders, the integer test both targets use to
// keep the sizes streak allows but a fuzz run cannot afford out of the run, and how a target
// reports a finding its sanitizers do not see.

#include <array>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string_view>

namespace streak::fuzz {

// method_options_fuzz reads its input as text lines:
//   METHOD or METHOD?QUERY   the first line: the method name (-m) and, after '?', options
//                            parsed by OptionMap::parseQuery (as a builtin:NAME?k=v spec's)
//   KEY=VALUE                one `--option KEY=VALUE` each: split at the first '=' as the
//                            command line does, then OptionMap::set
//   @SETTING=VALUE           the render, not the method's options (the prefixes below):
//                            aa 1..4, size WxH (8x8 without), scene one of kRenderScenes,
//                            seed, and the flags grid (--sample-grid) and unlit (--shading);
//                            at most kMaxImageSamples samples, width x height x aa^2, in all
inline constexpr std::string_view kAa = "@aa=", kSize = "@size=", kScene = "@scene=", kSeed = "@seed=";
inline constexpr std::string_view kGrid = "@grid", kUnlit = "@unlit";
inline constexpr int kMaxAa = 4, kMaxImageSamples = 64;

// The scenes a created CPU renderer renders (@scene=NAME; the first without), loaded once:
// every built-in, cubes with few enough cubes that a render stays within milliseconds.
struct RenderScene {
    std::string_view name;
    std::string_view spec;
};
inline constexpr std::array<RenderScene, 7> kRenderScenes{{
    {"crossing", "builtin:crossing"},
    {"twist", "builtin:twist"},
    {"rotating-cube", "builtin:rotating-cube?keys=3"},
    {"translucent", "builtin:translucent"},
    {"fence", "builtin:fence?bars=5&travel=2"},
    {"pan", "builtin:pan"},
    {"cubes", "builtin:cubes?n=12&keys=3"},
}};

// An int as OptionMap::getInt reads it (std::from_chars over the whole text), or none where
// getInt throws whatever the range.
inline std::optional<int> parseInt(std::string_view text) {
    int value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
    return value;
}

// A wrong result: said on stderr, then abort(), which libFuzzer reports as a crash with the input.
[[noreturn]] inline void finding(std::string_view what) {
    std::fprintf(stderr, "finding: %.*s\n", int(what.size()), what.data());
    std::abort();
}

}  // namespace streak::fuzz
