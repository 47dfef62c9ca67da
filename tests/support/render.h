#pragma once

// Rendering a scene with a method by name, as tests do.

#include "methods/registry.h"
#include "scene/scene.h"
#include "scene/shading.h"
#include "util/options.h"
#include "util/stats.h"

#include <string>

namespace streak::test {

inline Image render(const std::string& method, const Scene& scene, int width, int height, OptionMap options, RenderStats* stats = nullptr,
                    ShadingMode shading = ShadingMode::Unlit, int aa = 1, bool isGridPattern = false) {
    std::unique_ptr<Renderer> renderer = createRenderer(method, options);
    RenderSettings settings;
    settings.width = width, settings.height = height, settings.shading = shading, settings.aa = aa;
    settings.isGridPattern = isGridPattern;
    RenderStats local;
    RenderContext context{stats ? *stats : local};
    return renderer->render(scene, settings, context);
}

inline OptionMap withOption(const std::string& key, const std::string& value) {
    OptionMap o;
    o.set(key, value);
    return o;
}

}  // namespace streak::test
