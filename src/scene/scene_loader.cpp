#include "scene/scene_loader.h"

#include "scene/builtin_scenes.h"
#include "scene/mesh_file.h"
#include "scene/mesh_sequence.h"
#include "util/error.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string_view>

namespace streak {

bool isSceneFileSpec(const std::string& spec) { return isGltfSpec(spec) || (!spec.starts_with("builtin:") && isMeshFilePath(spec)); }

bool isGltfSpec(const std::string& spec) {
    std::string extension = std::filesystem::path(spec).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return !spec.starts_with("builtin:") && (extension == ".gltf" || extension == ".glb");
}

Scene loadScene(const std::string& spec, const GltfOptions& gltf, RenderStats* stats) {
    constexpr std::string_view kBuiltin = "builtin:";
    if (spec.starts_with(kBuiltin)) {
        const std::string_view rest = std::string_view(spec).substr(kBuiltin.size());
        const std::size_t q = rest.find('?');
        const std::string_view name = rest.substr(0, q);
        OptionMap options = q == std::string_view::npos ? OptionMap("scene '" + spec + "'")
                                                        : OptionMap::parseQuery(rest.substr(q + 1), "scene '" + spec + "'");
        return makeBuiltinScene(name, std::move(options));
    }
    if (isMeshFilePath(spec)) return loadMeshSequence(spec, gltf, stats);  // a file or a numbered sequence
    std::error_code ec;
    if (!std::filesystem::is_regular_file(spec, ec))
        throw Error("cannot read scene '" + spec + "': no such file (built-in scenes are named builtin:NAME, see 'streak scenes')");
    if (!isGltfSpec(spec)) throw Error("cannot load scene '" + spec + "': streak reads glTF 2.0 files (.gltf, .glb), OBJ and PLY meshes and sequences (.obj, .ply) and builtin:NAME scenes");
    return loadGltf(spec, gltf, stats);
}

}  // namespace streak
