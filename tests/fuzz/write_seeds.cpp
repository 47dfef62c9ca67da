// Writes the fuzz targets' seeds and dictionaries into the folder given as the argument; CTest
// runs it (Fuzz.Seeds) before the fuzz tests.
//   gltf/         tests/support/gltf_samples.h, as .gltf and .glb (gltf_loader_fuzz)
//   builtin/      specs after "builtin:" (builtin_scene_fuzz): every built-in scene alone, with
//                 each option at the ends of its range, with all of them at once, in the range
//   method/       method_options_fuzz inputs (fuzz/fuzz_inputs.h): every method alone, with
//                 its options likewise, as --option lines and as a query, and rendering each
//                 scene with every option at its first value
//   builtin.dict  and method.dict: the names, KEY= for every option, the input syntax, numbers
// The options each scene and method takes come from its own errors (an unknown key lists the
// keys it takes, a non-number names the key's range), so the seeds follow when a scene, a
// method or an option is added; an error no longer read that way stops this with a message.

#include "fuzz/fuzz_inputs.h"
#include "methods/registry.h"
#include "scene/builtin_scenes.h"
#include "support/gltf_samples.h"
#include "util/error.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <string>
#include <vector>

namespace {

using namespace streak;

// A built-in scene or a method, made from options (throws Error as its factory does).
struct Maker {
    std::string name;
    std::function<void(OptionMap)> make;
};

struct Option {
    std::string key;
    std::vector<std::string> values;  ///< that the maker takes
};

[[noreturn]] void fail(const std::string& message) {
    std::fprintf(stderr, "write_seeds: %s\n", message.c_str());
    std::exit(1);
}

OptionMap optionsOf(const std::vector<std::pair<std::string, std::string>>& pairs) {
    OptionMap options;
    for (const auto& [key, value] : pairs) options.set(key, value);
    return options;
}

// The message of the Error the maker throws for these options, or "" when it makes one.
std::string errorOf(const Maker& maker, const std::vector<std::pair<std::string, std::string>>& pairs) {
    try {
        maker.make(optionsOf(pairs));
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

// The text between `open` and the next `close` in `text`, or "" when absent.
std::string between(const std::string& text, const std::string& open, char close) {
    const std::size_t begin = text.find(open);
    if (begin == std::string::npos) return "";
    const std::size_t end = text.find(close, begin + open.size());
    return end == std::string::npos ? "" : text.substr(begin + open.size(), end - begin - open.size());
}

// Each option the maker takes (OptionMap::rejectUnknown lists them), with the ends of its range
// (getInt and getDouble name it for a non-number) or, for a key without one, examples it takes.
std::vector<Option> optionsTaken(const Maker& maker) {
    const std::string unknown = errorOf(maker, {{"fuzz-no-such-key", "1"}});
    if (unknown.ends_with("(it takes none)")) return {};
    std::string keys = between(unknown, "(it takes: ", ')');
    if (keys.empty()) fail(maker.name + ": the keys it takes are not in its error for an unknown key: '" + unknown + "'");
    std::vector<Option> options;
    for (std::size_t at = 0; at <= keys.size();) {
        const std::size_t comma = std::min(keys.find(", ", at), keys.size());
        Option option{keys.substr(at, comma - at), {}};
        const std::string range = between(errorOf(maker, {{option.key, "x"}}), " in [", ']');
        const std::size_t separator = range.find(", ");
        if (separator != std::string::npos) {
            option.values = {range.substr(0, separator), range.substr(separator + 2)};
        } else {
            for (const char* example : {"1", "0.5", "1,2,3,4,5"})
                if (errorOf(maker, {{option.key, example}}).empty()) option.values.push_back(example);
        }
        options.push_back(option);
        at = comma + 2;
    }
    return options;
}

class Folder {
public:
    explicit Folder(std::filesystem::path path) : m_path(std::move(path)) { std::filesystem::create_directories(m_path); }
    void write(const std::string& name, const std::string& bytes) const {
        std::ofstream(m_path / name, std::ios::binary) << bytes;
    }
    void write(const std::string& name, const std::vector<std::uint8_t>& bytes) const {
        write(name, std::string(bytes.begin(), bytes.end()));
    }
    // Writes the next numbered seed.
    void seed(const std::string& bytes) { write("seed-" + std::to_string(++m_count), bytes); }

private:
    std::filesystem::path m_path;
    int m_count = 0;
};

// A libFuzzer dictionary: one quoted token a line, with \" \\ and \xNN escapes.
std::string dictionary(const std::set<std::string>& tokens) {
    std::string text;
    for (const std::string& token : tokens) {
        text += '"';
        for (const unsigned char c : token) {
            char hex[5];
            std::snprintf(hex, sizeof hex, "\\x%02x", c);
            text += c == '"' || c == '\\' ? std::string{'\\', char(c)} : c >= 32 && c < 127 ? std::string(1, char(c)) : hex;
        }
        text += "\"\n";
    }
    return text;
}

// Seeds of the maker's options: one per option value, all at their first value, all at their
// last; `spell` turns (key, value) pairs into the target's input.
void optionSeeds(Folder& folder, const std::vector<Option>& options,
                 const std::function<std::string(const std::vector<std::pair<std::string, std::string>>&)>& spell) {
    folder.seed(spell({}));
    std::vector<std::pair<std::string, std::string>> firsts, lasts;
    for (const Option& option : options) {
        for (const std::string& value : option.values) folder.seed(spell({{option.key, value}}));
        if (option.values.empty()) continue;
        firsts.emplace_back(option.key, option.values.front());
        lasts.emplace_back(option.key, option.values.back());
    }
    if (firsts.size() > 1) folder.seed(spell(firsts)), folder.seed(spell(lasts));
}

std::string query(const std::vector<std::pair<std::string, std::string>>& pairs) {
    std::string text;
    for (const auto& [key, value] : pairs) text += (text.empty() ? "" : "&") + key + "=" + value;
    return text;
}

const std::set<std::string> kNumbers{"0", "-1", "65536", "2147483647", "2147483648", "1e308", "1e-320", "nan", "inf",
                                     "-0", "0x1p3", " 1", "+1", "1.5"};

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: write_seeds FOLDER\n");
        return 2;
    }
    const std::filesystem::path root = argv[1];
    std::filesystem::remove_all(root);  // no seeds of a scene or method since removed
    const Folder gltf(root / "gltf");
    gltf.write("skinned.gltf", test::skinnedTexturedTriangle().gltfBytes());
    gltf.write("skinned.glb", test::skinnedTexturedTriangle().glb());
    gltf.write("morphing.gltf", test::morphingStripWithCamera().gltfBytes());
    gltf.write("morphing.glb", test::morphingStripWithCamera().glb());

    Folder builtin(root / "builtin");
    std::set<std::string> builtinTokens = kNumbers;
    builtinTokens.insert({"?", "&", "="});
    for (const BuiltinSceneInfo& info : builtinScenes()) {
        const std::string name(info.name);
        const std::vector<Option> options = optionsTaken({name, [&](OptionMap o) { makeBuiltinScene(name, std::move(o)); }});
        optionSeeds(builtin, options, [&](const auto& pairs) { return pairs.empty() ? name : name + "?" + query(pairs); });
        builtinTokens.insert(name);
        for (const Option& option : options) builtinTokens.insert(option.key + "=");
    }

    Folder method(root / "method");
    std::set<std::string> methodTokens = kNumbers;
    methodTokens.insert({"\n", "?", "&", "=", std::string(fuzz::kAa), std::string(fuzz::kSize), std::string(fuzz::kScene),
                         std::string(fuzz::kSeed), std::string(fuzz::kGrid), std::string(fuzz::kUnlit)});
    for (const fuzz::RenderScene& scene : fuzz::kRenderScenes) methodTokens.insert(std::string(scene.name));
    for (const MethodInfo& info : registeredMethods()) {
        const std::string name(info.name);
        const std::vector<Option> options = optionsTaken({name, [&](OptionMap o) { createRenderer(name, std::move(o)); }});
        optionSeeds(method, options, [&](const auto& pairs) {
            std::string text = name;
            for (const auto& [key, value] : pairs) text += "\n" + key + "=" + value;
            return text;
        });
        std::vector<std::pair<std::string, std::string>> firsts;
        for (const Option& option : options)
            if (!option.values.empty()) firsts.emplace_back(option.key, option.values.front());
        method.seed(name + "?" + query(firsts));
        std::string minimal = name;
        for (const auto& [key, value] : firsts) minimal += "\n" + key + "=" + value;
        for (const fuzz::RenderScene& scene : fuzz::kRenderScenes)
            method.seed(minimal + "\n" + std::string(fuzz::kScene) + std::string(scene.name) + "\n" + std::string(fuzz::kAa) + "2\n" +
                        std::string(fuzz::kSize) + "4x3");
        method.seed(minimal + "\n" + std::string(fuzz::kGrid) + "\n" + std::string(fuzz::kUnlit) + "\n" + std::string(fuzz::kSeed) +
                    "3\n" + std::string(fuzz::kAa) + std::to_string(fuzz::kMaxAa) + "\n" + std::string(fuzz::kSize) + "1x4");
        methodTokens.insert(name);
        for (const Option& option : options) methodTokens.insert(option.key + "=");
    }
    Folder(root).write("builtin.dict", dictionary(builtinTokens));
    Folder(root).write("method.dict", dictionary(methodTokens));
    return 0;
}
