#include "gpu/shader_library.h"

#include "util/error.h"

#include <vector>

namespace streak::gpu {

namespace {

std::string firstLines(const std::string& log, int n) {
    std::string out;
    std::size_t start = 0;
    for (int i = 0; i < n && start < log.size(); ++i) {
        const std::size_t end = log.find('\n', start);
        out += (out.empty() ? "" : " | ") + log.substr(start, end == std::string::npos ? std::string::npos : end - start);
        if (end == std::string::npos) break;
        start = end + 1;
    }
    return out;
}

// The first lines of a shader's or program's log when `status` failed, else empty.
template <class GetIv, class GetLog>
std::string failureLog(GLuint id, GLenum status, GetIv getIv, GetLog getLog) {
    GLint ok = 0;
    getIv(id, status, &ok);
    if (ok) return {};
    GLint length = 0;
    getIv(id, GL_INFO_LOG_LENGTH, &length);
    std::string log(std::size_t(std::max(length, 1)), '\0');
    getLog(id, length, nullptr, log.data());
    const std::string text = firstLines(log.c_str(), 3);
    return text.empty() ? "(no log)" : text;
}

}  // namespace

const GlProgram& buildProgram(std::initializer_list<ShaderStage> stages, const std::map<std::string, std::string>& defines) {
    // Destroyed before the shared context, which was created before the first program.
    static std::map<std::string, GlProgram> built;
    std::string key;
    for (const ShaderStage& stage : stages) {
        key += std::to_string(stage.stage) + ":";
        for (std::string_view file : stage.files) key += std::string(file) + ",";
    }
    for (const auto& [name, value] : defines) key += ";" + name + "=" + value;
    if (const auto found = built.find(key); found != built.end()) return found->second;

    GlProgram program;
    std::vector<GlShader> shaders;
    std::string names;
    for (const ShaderStage& stage : stages) {
        // Each file starts on its own source string, so the driver's line numbers read
        // "string:line" with strings counted from 0 = the preamble.
        std::string preamble = "#version 450 core\n";
        // Shared files may need to know their stage (GLSL predefines no such macro).
        preamble += stage.stage == GL_FRAGMENT_SHADER ? "#define STAGE_FRAGMENT 1\n"
                    : stage.stage == GL_COMPUTE_SHADER ? "#define STAGE_COMPUTE 1\n"
                    : stage.stage == GL_GEOMETRY_SHADER ? "#define STAGE_GEOMETRY 1\n"
                                                         : "#define STAGE_VERTEX 1\n";
        for (const auto& [name, value] : defines) preamble += "#define " + name + " " + value + "\n";
        std::vector<std::string> texts{preamble};
        std::string stageNames;
        for (std::string_view file : stage.files) {
            const auto found = embeddedShaders().find(file);
            if (found == embeddedShaders().end()) throw RenderFailure("OpenGL: no embedded shader '" + std::string(file) + "'");
            texts.emplace_back("#line 1 " + std::to_string(texts.size()) + "\n" + std::string(found->second));
            stageNames += (stageNames.empty() ? "" : "+") + std::string(file);
        }
        std::vector<const char*> pointers;
        for (const std::string& t : texts) pointers.push_back(t.c_str());
        GlShader& shader = shaders.emplace_back(stage.stage);
        glShaderSource(shader.id(), GLsizei(pointers.size()), pointers.data(), nullptr);
        glCompileShader(shader.id());
        if (const std::string log = failureLog(shader.id(), GL_COMPILE_STATUS, glGetShaderiv, glGetShaderInfoLog); !log.empty())
            throw RenderFailure("OpenGL: shader " + stageNames + " does not compile: " + log);
        glAttachShader(program.id(), shader.id());
        names += (names.empty() ? "" : ", ") + stageNames;
    }
    glLinkProgram(program.id());
    if (const std::string log = failureLog(program.id(), GL_LINK_STATUS, glGetProgramiv, glGetProgramInfoLog); !log.empty())
        throw RenderFailure("OpenGL: program " + names + " does not link: " + log);
    return built.emplace(key, std::move(program)).first->second;
}

}  // namespace streak::gpu
