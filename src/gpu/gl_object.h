#pragma once

#include <epoxy/gl.h>

#include <cstddef>
#include <memory>
#include <string>
#include <utility>

namespace streak::gpu {

// GlObject owns one GL object name and deletes it with its scope, so no path through a render
// (an Error thrown halfway included) leaks GPU memory. Move-only. The context must be current.
template <class Traits>
class GlObject {
public:
    GlObject() : m_id(Traits::create()) {}
    explicit GlObject(GLenum target) : m_id(Traits::create(target)) {}
    ~GlObject() { reset(); }
    GlObject(GlObject&& o) noexcept : m_id(std::exchange(o.m_id, 0)) {}
    GlObject& operator=(GlObject&& o) noexcept {
        if (this != &o) reset(), m_id = std::exchange(o.m_id, 0);
        return *this;
    }
    GlObject(const GlObject&) = delete;
    GlObject& operator=(const GlObject&) = delete;

    GLuint id() const { return m_id; }

private:
    void reset() {
        if (m_id) Traits::destroy(m_id);
        m_id = 0;
    }
    GLuint m_id = 0;
};

struct BufferTraits {
    static GLuint create() { GLuint id = 0; glCreateBuffers(1, &id); return id; }
    static void destroy(GLuint id) { glDeleteBuffers(1, &id); }
};
struct TextureTraits {
    static GLuint create(GLenum target) { GLuint id = 0; glCreateTextures(target, 1, &id); return id; }
    static void destroy(GLuint id) { glDeleteTextures(1, &id); }
};
struct VertexArrayTraits {
    static GLuint create() { GLuint id = 0; glCreateVertexArrays(1, &id); return id; }
    static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); }
};
struct FramebufferTraits {
    static GLuint create() { GLuint id = 0; glCreateFramebuffers(1, &id); return id; }
    static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); }
};
struct QueryTraits {
    static GLuint create(GLenum target) { GLuint id = 0; glCreateQueries(target, 1, &id); return id; }
    static void destroy(GLuint id) { glDeleteQueries(1, &id); }
};
struct ProgramTraits {
    static GLuint create() { return glCreateProgram(); }
    static void destroy(GLuint id) { glDeleteProgram(id); }
};
struct ShaderTraits {
    static GLuint create(GLenum stage) { return glCreateShader(stage); }
    static void destroy(GLuint id) { glDeleteShader(id); }
};

using GlVertexArray = GlObject<VertexArrayTraits>;
using GlFramebuffer = GlObject<FramebufferTraits>;
using GlQuery = GlObject<QueryTraits>;
using GlProgram = GlObject<ProgramTraits>;
using GlShader = GlObject<ShaderTraits>;

// A buffer with immutable storage of a known size.
class GlBuffer {
public:
    GlBuffer() = default;
    // size bytes, with `data` (may be null) copied in; flags as glNamedBufferStorage takes.
    GlBuffer(std::size_t size, const void* data = nullptr, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);
    template <class Container>
    static GlBuffer from(const Container& c, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT) {
        return GlBuffer(c.size() * sizeof(c[0]), c.empty() ? nullptr : c.data(), flags);
    }

    GLuint id() const { return m_buffer ? m_buffer->id() : 0; }
    std::size_t size() const { return m_size; }
    void bindStorage(GLuint binding) const { glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, id()); }
    void upload(const void* data, std::size_t bytes, std::size_t offset = 0) const { glNamedBufferSubData(id(), GLintptr(offset), GLsizeiptr(bytes), data); }
    void download(void* data, std::size_t bytes, std::size_t offset = 0) const { glGetNamedBufferSubData(id(), GLintptr(offset), GLsizeiptr(bytes), data); }

private:
    // Zero-sized buffers are legal in streak (an empty scene) but not in GL: they get 16 bytes.
    std::unique_ptr<GlObject<BufferTraits>> m_buffer;
    std::size_t m_size = 0;
};

// A 2D texture with immutable storage.
class GlTexture {
public:
    GlTexture() = default;
    GlTexture(GLenum internalFormat, int width, int height, int levels = 1);

    GLuint id() const { return m_texture ? m_texture->id() : 0; }
    int width() const { return m_width; }
    int height() const { return m_height; }

private:
    std::unique_ptr<GlObject<TextureTraits>> m_texture;
    int m_width = 0, m_height = 0;
};

// Throws Error naming the GL error and `what` if GL recorded one since the last check.
void checkGlError(const std::string& what);

}  // namespace streak::gpu
