#include "scene/scene_loader.h"

#include "scene/builtin_scenes.h"
#include "util/error.h"

#include <filesystem>
#include <string_view>

namespace streak {

Scene loadScene(const std::string& spec) {
    constexpr std::string_view kBuiltin = "builtin:";
    if (spec.starts_with(kBuiltin)) {
        const std::string_view rest = std::string_view(spec).substr(kBuiltin.size());
        const std::size_t q = rest.find('?');
        const std::string_view name = rest.substr(0, q);
        OptionMap options = q == std::string_view::npos ? OptionMap("scene '" + spec + "'")
                                                        : OptionMap::parseQuery(rest.substr(q + 1), "scene '" + spec + "'");
        return makeBuiltinScene(name, std::move(options));
    }
    std::error_code ec;
    if (!std::filesystem::is_regular_file(spec, ec))
        throw Error("cannot read scene '" + spec + "': no such file (built-in scenes are named builtin:NAME, see 'streak scenes')");
    throw Error("cannot load scene '" + spec + "': only builtin:NAME scenes can be loaded by this version of streak");
}

}  // namespace streak
