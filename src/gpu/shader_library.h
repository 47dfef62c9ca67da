#pragma once

#include "gpu/gl_object.h"

#include <initializer_list>
#include <map>
#include <string>
#include <string_view>

namespace streak::gpu {

// The .glsl files of src/gpu/shaders and src/methods/*/shaders, embedded at build time
// (cmake/embed_shaders.cmake), by file name.
const std::map<std::string_view, std::string_view>& embeddedShaders();

// One stage of a program: its GL stage and the embedded files that make its source, in order.
// The version line, STAGE_VERTEX / STAGE_GEOMETRY / STAGE_FRAGMENT / STAGE_COMPUTE and
// `defines` ("NAME VALUE" each) come first; shared code (scene buffers,
// shading) is a file listed before the stage's own.
struct ShaderStage {
    GLenum stage;
    std::initializer_list<std::string_view> files;
};

// Compiles and links; Error with the driver's log (first line) and the file names on failure.
// Each distinct program (stages, files, defines) is built once on the shared context and kept
// for the process: the next frame reuses it, with the driver's compiled code (llvmpipe's JIT of
// the motion-path resolve takes seconds). Uniforms are the caller's to set before each use.
const GlProgram& buildProgram(std::initializer_list<ShaderStage> stages, const std::map<std::string, std::string>& defines = {});

}  // namespace streak::gpu
