#include "scene/mesh_file.h"

#include "scene/gltf_document.h"
#include "util/error.h"

#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>

namespace streak {

namespace {

std::string lowercaseExtension(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return extension;
}

std::string firstLine(const std::string& text) {
    const std::string line = text.substr(0, text.find('\n'));
    return line.empty() ? "unreadable" : line;
}

// A piece of a file quoted in a message: one line of printable characters, at most 40 of them.
std::string excerpt(const std::string& text) {
    std::string out;
    for (const char c : text.substr(0, 40)) out += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
    return "'" + out + (text.size() > 40 ? "...'" : "'");
}

// Appends the fan of a polygon's corners, checking each index and the triangle count.
void addPolygon(const std::vector<std::int64_t>& corners, std::size_t numVertices, std::size_t maxTriangles, const std::string& path,
                std::vector<glm::uvec3>& triangles) {
    for (const std::int64_t c : corners)
        if (c < 0 || std::uint64_t(c) >= numVertices)
            throw Error(path + ": a face names vertex " + std::to_string(c) + " of " + std::to_string(numVertices));
    if (corners.size() > 2 && triangles.size() + (corners.size() - 2) > maxTriangles)
        throw Error(path + ": the mesh has more than " + std::to_string(maxTriangles) + " triangles");
    for (std::size_t k = 1; k + 1 < corners.size(); ++k)
        triangles.emplace_back(std::uint32_t(corners[0]), std::uint32_t(corners[k]), std::uint32_t(corners[k + 1]));
}

MeshFile readObj(const std::string& path, const std::vector<std::uint8_t>& bytes, std::size_t maxTriangles) {
    tinyobj::ObjReaderConfig config;
    config.triangulate = false;  // faces are fanned here, in the file's vertex order
    config.vertex_color = false;
    config.mtl_search_path = "";
    tinyobj::ObjReader reader;
    const std::string text(bytes.begin(), bytes.end());
    if (!reader.ParseFromString(text, "", config)) throw Error(path + ": " + firstLine(reader.Error()));
    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    MeshFile mesh;
    for (std::size_t i = 0; i + 2 < attrib.vertices.size(); i += 3)
        mesh.positions.emplace_back(attrib.vertices[i], attrib.vertices[i + 1], attrib.vertices[i + 2]);
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        std::size_t next = 0;
        for (const unsigned int count : shape.mesh.num_face_vertices) {
            std::vector<std::int64_t> corners;
            for (unsigned int k = 0; k < count && next < shape.mesh.indices.size(); ++k) corners.push_back(shape.mesh.indices[next++].vertex_index);
            addPolygon(corners, mesh.positions.size(), maxTriangles, path, mesh.triangles);
        }
        // tinyobjloader counts a face's corners in a byte: a face of 256 or more would misalign
        // the faces after it.
        if (next != shape.mesh.indices.size()) throw Error(path + ": a face has 256 or more corners");
    }
    return mesh;
}

// PLY: a header of elements and their properties, then the elements' data, ASCII or binary.
class PlyReader {
public:
    PlyReader(const std::string& path, const std::vector<std::uint8_t>& bytes, std::size_t maxTriangles)
        : m_path(path), m_bytes(bytes), m_maxTriangles(maxTriangles) {}

    MeshFile read() {
        readHeader();
        MeshFile mesh;
        for (const Element& element : m_elements) {
            const bool isVertex = element.name == "vertex", isFace = element.name == "face";
            // A binary element's rows are at least their fixed properties' bytes: counts that the
            // file cannot hold are refused before anything is allocated for them.
            // ASCII rows take at least two characters a property (a digit and a separator).
            const std::size_t rowBytes = m_isAscii ? 2 * element.properties.size() : element.minBytes();
            if (element.count > 0 && remaining() / std::max<std::size_t>(1, rowBytes) < element.count)
                throw Error(m_path + ": the file is too short for its " + std::to_string(element.count) + " " + element.name + " elements");
            if (isVertex) mesh.positions.reserve(element.count);
            for (std::uint64_t row = 0; row < element.count; ++row) {
                glm::vec3 position(0.0f), velocity(0.0f);
                for (const Property& p : element.properties) {
                    if (p.isList) {
                        const std::int64_t n = wholeNumber(number(p.countType), 0, 1024, "a " + element.name + " list's length");
                        std::vector<std::int64_t> items;
                        for (std::int64_t k = 0; k < n; ++k) items.push_back(wholeNumber(number(p.type), -1, std::int64_t(1) << 40, "an index"));
                        if (isFace && (p.name == "vertex_indices" || p.name == "vertex_index"))
                            addPolygon(items, mesh.positions.size(), m_maxTriangles, m_path, mesh.triangles);
                        continue;
                    }
                    const double v = number(p.type);
                    if (!isVertex) continue;
                    if (p.name == "x") position.x = float(v);
                    else if (p.name == "y") position.y = float(v);
                    else if (p.name == "z") position.z = float(v);
                    else if (p.name == "vx") velocity.x = float(v);
                    else if (p.name == "vy") velocity.y = float(v);
                    else if (p.name == "vz") velocity.z = float(v);
                }
                if (isVertex) {
                    mesh.positions.push_back(position);
                    if (m_hasVelocities) mesh.velocities.push_back(velocity);
                }
            }
        }
        return mesh;
    }

private:
    struct Property {
        std::string name, type, countType;
        bool isList = false;
    };
    struct Element {
        std::string name;
        std::uint64_t count = 0;
        std::vector<Property> properties;
        std::size_t minBytes() const {
            std::size_t bytes = 0;
            for (const Property& p : properties) bytes += sizeOf(p.isList ? p.countType : p.type);
            return bytes;
        }
    };

    static std::size_t sizeOf(const std::string& type) {
        static const std::map<std::string, std::size_t> sizes{{"char", 1},  {"uchar", 1},  {"int8", 1},   {"uint8", 1},   {"short", 2},
                                                              {"ushort", 2}, {"int16", 2},  {"uint16", 2},  {"int", 4},     {"uint", 4},
                                                              {"int32", 4},  {"uint32", 4}, {"float", 4},   {"float32", 4}, {"double", 8},
                                                              {"float64", 8}};
        const auto it = sizes.find(type);
        return it == sizes.end() ? 0 : it->second;
    }

    std::size_t remaining() const { return m_bytes.size() - m_pos; }

    // A number that must be whole and in [lo, hi] (a list's length, an index).
    std::int64_t wholeNumber(double v, std::int64_t lo, std::int64_t hi, const std::string& what) const {
        if (!(v >= double(lo) && v <= double(hi)) || v != std::floor(v))
            throw Error(m_path + ": " + what + " is " + std::to_string(v) + ", not a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
        return std::int64_t(v);
    }

    void readHeader() {
        auto line = [&] {
            const std::size_t end = std::find(m_bytes.begin() + std::ptrdiff_t(m_pos), m_bytes.end(), std::uint8_t('\n')) - m_bytes.begin();
            if (end == m_bytes.size()) throw Error(m_path + ": the PLY header has no end_header");
            std::string text(m_bytes.begin() + std::ptrdiff_t(m_pos), m_bytes.begin() + std::ptrdiff_t(end));
            if (!text.empty() && text.back() == '\r') text.pop_back();
            m_pos = end + 1;
            return text;
        };
        if (line() != "ply") throw Error(m_path + ": not a PLY file (no 'ply' line)");
        bool hasFormat = false;
        for (std::string text = line(); text != "end_header"; text = line()) {
            std::istringstream in(text);
            std::string word;
            in >> word;
            if (word == "format") {
                std::string format;
                in >> format;
                if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
                    throw Error(m_path + ": unknown PLY format " + excerpt(format));
                m_isAscii = format == "ascii";
                m_isBigEndian = format == "binary_big_endian";
                hasFormat = true;
            } else if (word == "element") {
                Element e;
                if (!(in >> e.name >> e.count)) throw Error(m_path + ": a bad PLY element line " + excerpt(text));
                m_elements.push_back(e);
            } else if (word == "property") {
                if (m_elements.empty()) throw Error(m_path + ": a PLY property before any element");
                Property p;
                in >> p.type;
                if (p.type == "list") {
                    p.isList = true;
                    in >> p.countType >> p.type;
                    if (sizeOf(p.countType) == 0) throw Error(m_path + ": unknown PLY type " + excerpt(p.countType));
                }
                in >> p.name;
                if (sizeOf(p.type) == 0 || p.name.empty()) throw Error(m_path + ": a bad PLY property line " + excerpt(text));
                m_elements.back().properties.push_back(p);
            } else if (word != "comment" && word != "obj_info" && !word.empty()) {
                throw Error(m_path + ": an unknown PLY header line " + excerpt(text));
            }
        }
        if (!hasFormat) throw Error(m_path + ": the PLY header has no format line");
        for (const Element& e : m_elements) {
            if (e.name != "vertex") continue;
            std::map<std::string, bool> has;
            for (const Property& p : e.properties) has[p.name] = !p.isList;
            if (!has["x"] || !has["y"] || !has["z"]) throw Error(m_path + ": the PLY vertices have no x, y and z");
            m_hasVelocities = has["vx"] && has["vy"] && has["vz"];
        }
    }

    // The next number of `type`, as a double.
    double number(const std::string& type) {
        if (m_isAscii) {
            while (m_pos < m_bytes.size() && std::isspace(m_bytes[m_pos])) ++m_pos;
            const std::size_t start = m_pos;
            while (m_pos < m_bytes.size() && !std::isspace(m_bytes[m_pos])) ++m_pos;
            if (start == m_pos) throw Error(m_path + ": the PLY data ends early");
            const std::string token(m_bytes.begin() + std::ptrdiff_t(start), m_bytes.begin() + std::ptrdiff_t(m_pos));
            char* end = nullptr;
            const double v = std::strtod(token.c_str(), &end);
            if (*end != '\0') throw Error(m_path + ": " + excerpt(token) + " is not a number");
            return v;
        }
        const std::size_t size = sizeOf(type);
        if (remaining() < size) throw Error(m_path + ": the PLY data ends early");
        std::uint8_t raw[8];
        std::memcpy(raw, m_bytes.data() + m_pos, size);
        m_pos += size;
        if (m_isBigEndian != (std::endian::native == std::endian::big)) std::reverse(raw, raw + size);
        auto as = [&](auto value) {
            std::memcpy(&value, raw, sizeof value);
            return double(value);
        };
        if (type == "char" || type == "int8") return as(std::int8_t());
        if (type == "uchar" || type == "uint8") return as(std::uint8_t());
        if (type == "short" || type == "int16") return as(std::int16_t());
        if (type == "ushort" || type == "uint16") return as(std::uint16_t());
        if (type == "int" || type == "int32") return as(std::int32_t());
        if (type == "uint" || type == "uint32") return as(std::uint32_t());
        if (type == "float" || type == "float32") return as(float());
        return as(double());
    }

    const std::string& m_path;
    const std::vector<std::uint8_t>& m_bytes;
    std::size_t m_maxTriangles;
    std::size_t m_pos = 0;
    bool m_isAscii = true, m_isBigEndian = false, m_hasVelocities = false;
    std::vector<Element> m_elements;
};

}  // namespace

bool isMeshFilePath(const std::string& path) {
    const std::string extension = lowercaseExtension(path);
    return extension == ".obj" || extension == ".ply";
}

// An OBJ's velocities: the sidecar NAME.vel beside NAME.obj, if there is one: "vx vy vz" per
// vertex in the OBJ's vertex order, one to a line, '#' lines being comments.
std::vector<glm::vec3> readObjVelocities(const std::string& path, std::size_t numVertices, std::uint64_t maxBytes) {
    const std::string sidecar = std::filesystem::path(path).replace_extension(".vel").string();
    std::error_code ec;
    if (!std::filesystem::exists(sidecar, ec)) return {};
    const std::vector<std::uint8_t> bytes = gltf::readFileBytes(sidecar, maxBytes);
    std::istringstream in(std::string(bytes.begin(), bytes.end()));
    std::vector<glm::vec3> velocities;
    for (std::string line; std::getline(in, line);) {
        const std::size_t start = line.find_first_not_of(" \t\r");
        if (start == std::string::npos || line[start] == '#') continue;  // blank, or a comment
        if (line.back() == '\r') line.pop_back();
        std::istringstream fields(line);
        glm::vec3 v;
        std::string extra;
        if (!(fields >> v.x >> v.y >> v.z) || (fields >> extra) || !std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
            throw Error(sidecar + ": line " + excerpt(line) + " is not three numbers vx vy vz");
        velocities.push_back(v);
    }
    if (velocities.size() != numVertices)
        throw Error(sidecar + ": " + std::to_string(velocities.size()) + " velocities for the " + std::to_string(numVertices) + " vertices of " + path);
    return velocities;
}

MeshFile readMeshFile(const std::string& path, std::uint64_t maxBytes, std::size_t maxTriangles) {
    const std::vector<std::uint8_t> bytes = gltf::readFileBytes(path, maxBytes);
    const bool isObj = lowercaseExtension(path) == ".obj";
    MeshFile mesh = isObj ? readObj(path, bytes, maxTriangles) : PlyReader(path, bytes, maxTriangles).read();
    if (isObj) mesh.velocities = readObjVelocities(path, mesh.positions.size(), maxBytes);
    if (mesh.positions.empty() || mesh.triangles.empty()) throw Error(path + ": the mesh has no triangles");
    if (mesh.positions.size() > std::numeric_limits<std::uint32_t>::max()) throw Error(path + ": too many vertices");
    return mesh;
}

}  // namespace streak
