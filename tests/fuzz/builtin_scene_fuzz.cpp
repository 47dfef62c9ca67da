// libFuzzer target: the built-in scene specs, loadScene("builtin:" + input), which splits the
// name from its ?key=value&... query (OptionMap::parseQuery) and builds the scene with its
// options. Loading must end in a scene that validateScene accepts, with no position NaN or
// infinite, or in a streak::Error: anything else (a crash, a sanitizer report, another
// exception, a leak, a hang, a huge allocation) is a finding.
//
// One size is left out on purpose: cubes takes n up to 1000000 and keys up to 64, so one spec
// can ask for 64 M key poses of 24 vertices (n = 1000000 keys = 2 alone takes 2 GB and 7 s in a
// release build; keys = 64, some 45 GB); inputs asking for more than kMaxCubeKeys cubes x keys
// are rejected before loading, so that the run explores the parser instead.

#include "fuzz/fuzz_inputs.h"
#include "scene/scene_loader.h"
#include "util/error.h"
#include "util/options.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace {

constexpr long long kMaxCubeKeys = 8000;  // n x keys: 4.6 MB of poses, a few ms under ASan

// True when `rest` (the spec after "builtin:") asks cubes for more than kMaxCubeKeys, its
// options read as the loader reads them (cubes takes n = 1000 and keys = 2 when not given).
bool asksForTooManyCubes(std::string_view rest) {
    const std::size_t q = rest.find('?');
    if (q == std::string_view::npos || rest.substr(0, q) != "cubes") return false;
    try {
        streak::OptionMap options = streak::OptionMap::parseQuery(rest.substr(q + 1), "probe");
        const auto value = [&](const char* key, int fallback) {
            return options.has(key) ? streak::fuzz::parseInt(options.getString(key, "")).value_or(0) : fallback;
        };
        return (long long)value("n", 1000) * value("keys", 2) > kMaxCubeKeys;
    } catch (const streak::Error&) {
        return false;  // the loader throws the same Error
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view rest(reinterpret_cast<const char*>(data), size);
    if (asksForTooManyCubes(rest)) return -1;  // not added to the corpus
    try {
        streak::Scene scene = streak::loadScene("builtin:" + std::string(rest));
        if (streak::validateScene(scene).numNonFinite != 0)
            streak::fuzz::finding("a built-in scene has positions that are not finite");
    } catch (const streak::Error&) {
    }
    return 0;
}
