// Writes the fuzz target's own seeds (tests/support/gltf_samples.h, as .gltf and .glb) into the
// folder given as the argument. CTest runs it before GltfLoader.Fuzz.

#include "support/gltf_samples.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: write_seeds FOLDER\n");
        return 2;
    }
    const std::filesystem::path folder = argv[1];
    std::filesystem::create_directories(folder);
    auto write = [&](const std::string& name, const std::vector<std::uint8_t>& bytes) {
        std::ofstream(folder / name, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    };
    write("skinned.gltf", streak::test::skinnedTexturedTriangle().gltfBytes());
    write("skinned.glb", streak::test::skinnedTexturedTriangle().glb());
    write("morphing.gltf", streak::test::morphingStripWithCamera().gltfBytes());
    write("morphing.glb", streak::test::morphingStripWithCamera().glb());
    return 0;
}
