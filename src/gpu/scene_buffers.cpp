#include "gpu/scene_buffers.h"

#include "util/error.h"

#include <glm/ext/scalar_constants.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>

namespace streak::gpu {

namespace {

// The std140 block SceneBlock of scene.glsl.
struct SceneBlock {
    glm::vec4 eyeOpen, eyeClose, rotationOpen, rotationClose, slerp, projection, toLight, lightColor, ambient, background;
    glm::ivec4 viewport, flags;
    glm::vec4 shutter;
    glm::vec4 shutterCurve[ShutterCurve::kMaxPoints];
};

struct MaterialData {  // std430, as scene.glsl's MaterialData
    glm::vec4 baseColorOpacity, phong;
    glm::ivec4 info;
};

GLint glWrap(WrapMode mode) {
    switch (mode) {
    case WrapMode::ClampToEdge: return GL_CLAMP_TO_EDGE;
    case WrapMode::MirroredRepeat: return GL_MIRRORED_REPEAT;
    case WrapMode::Repeat:
    default: return GL_REPEAT;
    }
}

glm::vec4 quaternion(const glm::quat& q) { return {q.x, q.y, q.z, q.w}; }

// Whether a triangle's corners and normals are the same at every key of its mesh.
bool isStillAllKeys(const FlatGeometry& geometry, const FlatTriangle& tri) {
    const Mesh& mesh = geometry.meshOf(tri);
    const std::size_t nv = mesh.numVertices();
    const std::uint32_t base = geometry.meshVertexOffset(tri.mesh);
    for (int k = 1; k < mesh.numKeys; ++k)
        for (int i = 0; i < 3; ++i) {
            const std::size_t v = tri.vertices[i] - base;
            if (mesh.positions[std::size_t(k) * nv + v] != mesh.positions[v]) return false;
            if (mesh.hasNormals() && mesh.normals[std::size_t(k) * nv + v] != mesh.normals[v]) return false;
        }
    return true;
}

}  // namespace

SceneBuffers::SceneBuffers(const FlatGeometry& geometry, int width, int height, int aa, bool isGridPattern, ShadingMode shading) {
    const Scene& scene = geometry.scene();
    GLint stageUnits = 0, computeUnits = 0;
    glGetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &stageUnits);
    glGetIntegerv(GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS, &computeUnits);
    const int maxTextures = std::min(stageUnits, computeUnits);
    if (int(scene.textures.size()) > maxTextures)
        throw Error("the scene has " + std::to_string(scene.textures.size()) + " textures; this OpenGL driver's shaders take at most " +
                    std::to_string(maxTextures));

    std::vector<glm::uvec4> triangles, vertexInfo, meshes;
    std::vector<glm::vec4> keyPositions, keyNormals, attributes;
    int maxKeys = 2;
    for (std::uint32_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        maxKeys = std::max(maxKeys, mesh.numKeys);
        // y: the degree of the mesh's Bezier pieces (scene.glsl's motionWeights), 0 for linear keys.
        meshes.emplace_back(std::uint32_t(mesh.numKeys), mesh.interpolation == MotionInterpolation::Bezier ? std::uint32_t(mesh.bezierOrder()) : 0u,
                            mesh.hasNormals() ? 1u : 0u, 0u);
        const std::uint32_t keyBase = std::uint32_t(keyPositions.size());
        const std::size_t nv = mesh.numVertices();
        for (std::size_t v = 0; v < nv; ++v) {
            vertexInfo.emplace_back(m, keyBase + std::uint32_t(v), std::uint32_t(nv), 0u);
            attributes.push_back(mesh.color(std::uint32_t(v)));
            attributes.emplace_back(mesh.uv(std::uint32_t(v)), 0.0f, 0.0f);
        }
        for (std::size_t k = 0; k < mesh.positions.size(); ++k) {
            keyPositions.emplace_back(mesh.positions[k], 1.0f);
            keyNormals.emplace_back(mesh.hasNormals() ? mesh.normals[k] : glm::vec3(0.0f), 0.0f);
        }
    }
    // (The flags of scene.glsl's kDoubleSidedBit and kStillBit above the material.)
    const bool isCameraStatic = scene.camera.isStatic();
    for (const FlatTriangle& tri : geometry.triangles()) {
        if (tri.material >= 0x40000000u) throw Error("the scene has more materials than the GL methods take (2^30)");
        triangles.emplace_back(tri.vertices, tri.material | (tri.isDoubleSided ? 0x80000000u : 0u) |
                                                 (isCameraStatic && isStillAllKeys(geometry, tri) ? 0x40000000u : 0u));
    }
    m_numTriangles = triangles.size();

    std::vector<MaterialData> materials;
    for (const Material& mat : scene.materials)
        materials.push_back({glm::vec4(mat.baseColor, mat.opacity), glm::vec4(mat.specular, mat.shininess, mat.alphaCutoff, 0.0f),
                             glm::ivec4(mat.baseColorTexture, int(mat.alphaMode), mat.doubleSided ? 1 : 0, mat.isTranslucent() ? 1 : 0)});

    m_storage.push_back(GlBuffer::from(triangles, 0));
    m_storage.push_back(GlBuffer::from(keyPositions, 0));
    m_storage.push_back(GlBuffer::from(keyNormals, 0));
    m_storage.push_back(GlBuffer::from(vertexInfo, 0));
    m_storage.push_back(GlBuffer::from(attributes, 0));
    m_storage.push_back(GlBuffer::from(meshes, 0));
    m_storage.push_back(GlBuffer::from(materials, 0));
    for (const GlBuffer& b : m_storage) m_uploadBytes += b.size();

    const Camera& camera = scene.camera;
    const float aspect = float(width) / float(height);
    const float f = 1.0f / std::tan(camera.verticalFov * 0.5f);
    SceneBlock block{};
    block.eyeOpen = glm::vec4(camera.open.position, 1.0f);
    block.eyeClose = glm::vec4(camera.close.position, 1.0f);
    block.rotationOpen = quaternion(camera.open.worldFromCamera);
    // glm::slerp's choices and its angle, so shaders need no acos (scene.glsl, slerpRotation).
    const float cosTheta = glm::dot(camera.open.worldFromCamera, camera.close.worldFromCamera);
    const glm::quat close = cosTheta < 0.0f ? -camera.close.worldFromCamera : camera.close.worldFromCamera;
    const float angle = std::acos(std::abs(cosTheta));
    block.rotationClose = quaternion(close);
    block.slerp = glm::vec4(angle, std::sin(angle), std::abs(cosTheta) > 1.0f - glm::epsilon<float>() ? 1.0f : 0.0f, 0.0f);
    block.projection = glm::vec4(f / aspect, f, camera.zNear, camera.isStatic() ? 0.0f : 1.0f);
    block.toLight = glm::vec4(scene.light.toLight, 0.0f);
    block.lightColor = glm::vec4(scene.light.color, 0.0f);
    block.ambient = glm::vec4(scene.light.ambient, 0.0f);
    block.background = glm::vec4(scene.background, 1.0f);
    block.viewport = glm::ivec4(width * aa, height * aa, width, height);
    // x: 0 unlit, 1 Phong, 2 the normal pass (shading.glsl's isLit, isNormalPass).
    block.flags = glm::ivec4(shading == ShadingMode::Phong ? 1 : shading == ShadingMode::Normal ? 2 : 0, aa, isGridPattern ? 1 : 0, 0);
    const Shutter& shutter = scene.shutter;
    const std::vector<glm::vec2>& points = shutter.curve.points();
    block.shutter = glm::vec4(shutter.rollingDuration, float(points.size()), shutter.isBox() ? 1.0f : 0.0f, shutter.curve.isBox() ? 1.0f : 0.0f);
    for (std::size_t i = 0; i < points.size(); ++i)
        block.shutterCurve[i] = glm::vec4(points[i], float(shutter.curve.exposureAt(points[i].x)), 0.0f);
    m_uniforms = GlBuffer(sizeof block, &block, 0);

    for (const Texture& texture : scene.textures) {
        GlTexture& gl = m_textures.emplace_back(GL_RGBA32F, texture.width(), texture.height(), texture.numLevels());
        for (int level = 0; level < texture.numLevels(); ++level)
            glTextureSubImage2D(gl.id(), level, 0, 0, texture.width(level), texture.height(level), GL_RGBA, GL_FLOAT,
                                &texture.texel(level, 0, 0));
        glTextureParameteri(gl.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        glTextureParameteri(gl.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(gl.id(), GL_TEXTURE_WRAP_S, glWrap(texture.wrapU()));
        glTextureParameteri(gl.id(), GL_TEXTURE_WRAP_T, glWrap(texture.wrapV()));
        glTextureParameteri(gl.id(), GL_TEXTURE_MAX_LEVEL, texture.numLevels() - 1);
        m_uploadBytes += std::size_t(texture.width()) * texture.height() * 16 * 4 / 3;
    }
    m_emptyTexture = GlTexture(GL_RGBA32F, 1, 1, 1);
    checkGlError("uploading the scene");

    m_defines["MAX_TEXTURES"] = std::to_string(std::max<std::size_t>(1, scene.textures.size()));
    m_defines["MAX_KEYS"] = std::to_string(maxKeys);
}

void SceneBuffers::bind(GLuint program) const {
    for (std::size_t i = 0; i < m_storage.size(); ++i) m_storage[i].bindStorage(GLuint(i));
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, m_uniforms.id());
    const int n = std::max<int>(1, int(m_textures.size()));
    std::vector<GLint> units(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
        units[std::size_t(i)] = i;
        glBindTextureUnit(GLuint(i), i < int(m_textures.size()) ? m_textures[std::size_t(i)].id() : m_emptyTexture.id());
    }
    const GLint location = glGetUniformLocation(program, "u_textures");
    if (location >= 0) glProgramUniform1iv(program, location, n, units.data());
}

}  // namespace streak::gpu
