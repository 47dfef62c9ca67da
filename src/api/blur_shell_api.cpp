// The blur shell through the public API: the trail its options need, and the shell scene.

#include "streak/blur_shell.h"

#include "api/api_internal.h"

#include "scene/blur_shell.h"
#include "util/options.h"

namespace streak::api {

namespace {

BlurShellOptions shellOptionsOf(const std::map<std::string, std::string>& options) {
    OptionMap map("shell");
    for (const auto& [key, value] : options) map.set(key, value);
    const BlurShellOptions shell = BlurShellOptions::read(map);
    map.rejectUnknown();
    return shell;
}

Trail trailOf(const BlurShellOptions& shell) { return Trail{shell.lengthSeconds, shell.subdivisions + 1}; }

}  // namespace

Trail blurShellTrail(const std::map<std::string, std::string>& options) { return trailOf(shellOptionsOf(options)); }

BlurShell blurShell(const Scene& trail, const std::map<std::string, std::string>& options) {
    const BlurShellOptions shellOptions = shellOptionsOf(options);
    const Scene::Impl& in = trail.impl();
    if (!in.canShowTrail(trailOf(shellOptions)))
        throw Error("the shell's glTF scene must be loaded over its trail (LoadOptions::trail = blurShellTrail(options))");
    const streak::BlurShell shell = buildBlurShell(in.scene, shellOptions);
    ShellScene shellScene = makeShellScene(in.scene, shell);
    auto impl = std::make_shared<Scene::Impl>();
    impl->spec = in.spec;
    impl->isGltf = false;  // a scene standing at T: no trail left to load
    impl->scene = std::move(shellScene.scene);
    BlurShell out{Scene::Impl::wrap(std::move(impl))};
    out.strips = shell.numStrips;
    for (std::size_t m = shellScene.firstShellMesh; m < out.scene.impl().scene.meshes.size(); ++m)
        out.triangles += out.scene.impl().scene.meshes[m].triangles.size();
    out.silhouetteEdges = shell.silhouetteEdges;
    return out;
}

}  // namespace streak::api
