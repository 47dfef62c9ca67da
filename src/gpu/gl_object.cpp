#include "gpu/gl_object.h"

#include "util/error.h"

#include <algorithm>
#include <cstdio>

namespace streak::gpu {

GlBuffer::GlBuffer(std::size_t size, const void* data, GLbitfield flags)
    : m_buffer(std::make_unique<GlObject<BufferTraits>>()), m_size(size) {
    glNamedBufferStorage(m_buffer->id(), GLsizeiptr(std::max<std::size_t>(size, 16)), size >= 16 ? data : nullptr, flags);
    if (data && size > 0 && size < 16) glNamedBufferSubData(m_buffer->id(), 0, GLsizeiptr(size), data);
    checkGlError("allocating a " + std::to_string(size) + "-byte buffer");
}

GlTexture::GlTexture(GLenum internalFormat, int width, int height, int levels)
    : m_texture(std::make_unique<GlObject<TextureTraits>>(GL_TEXTURE_2D)), m_width(width), m_height(height) {
    glTextureStorage2D(m_texture->id(), levels, internalFormat, width, height);
    checkGlError("allocating a " + std::to_string(width) + "x" + std::to_string(height) + " texture");
}

void checkGlError(const std::string& what) {
    const GLenum error = glGetError();
    if (error == GL_NO_ERROR) return;
    while (glGetError() != GL_NO_ERROR) {}
    const char* name = error == GL_OUT_OF_MEMORY ? "out of memory"
                       : error == GL_INVALID_VALUE ? "invalid value"
                       : error == GL_INVALID_OPERATION ? "invalid operation"
                       : error == GL_INVALID_ENUM ? "invalid enum"
                                                  : "error";
    throw RenderFailure("OpenGL " + std::string(name) + " (0x" + [&] {
        char hex[16];
        std::snprintf(hex, sizeof hex, "%04x", error);
        return std::string(hex);
    }() + ") " + what);
}

}  // namespace streak::gpu
