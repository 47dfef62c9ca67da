// libFuzzer target: the glTF loader on arbitrary bytes (.gltf JSON or .glb), from memory, with
// files off and small limits. Loading must end in a Scene or a streak::Error: anything else
// (a crash, a sanitizer report, a leak, a hang, a huge allocation) is a finding.

#include "scene/gltf_loader.h"
#include "util/error.h"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    streak::GltfOptions options;
    options.allowExternalFiles = false;
    options.frame = 5.0;  // inside most sample animations, so the samplers run
    options.shutter = 2.0;
    options.motionKeys = 3;
    options.limits.maxFileBytes = 1 << 24;
    options.limits.maxTexels = 1 << 20;
    options.limits.maxTriangles = 1 << 16;
    options.limits.maxVertexWork = 1 << 20;
    try {
        streak::Scene scene = streak::loadGltfFromMemory({data, size}, "fuzz.gltf", "", options);
        streak::validateScene(scene);
    } catch (const streak::Error&) {
    }
    return 0;
}
