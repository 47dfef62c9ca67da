#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
}

namespace streak::gltf {

// Component types an accessor may use for one purpose (a bit mask).
enum ComponentTypes : std::uint32_t {
    kFloat = 1u << 0,
    kUnsignedByte = 1u << 1,
    kUnsignedShort = 1u << 2,
    kUnsignedInt = 1u << 3,
    kByte = 1u << 4,
    kShort = 1u << 5,
    kUnsignedInts = kUnsignedByte | kUnsignedShort | kUnsignedInt,
    kFloatOrNormalized = kFloat | kUnsignedByte | kUnsignedShort | kByte | kShort,
};

// AccessorReader reads glTF accessors (and buffer views) of a parsed model, trusting nothing
// tinygltf left unchecked: every index, the element type and component type, byteStride, and
// that every element lies inside its buffer view and the view inside its buffer, for the dense
// part and for sparse substitutions alike. It throws Error("<what> (accessor N): problem").
// An accessor without a buffer view reads as zeros (then sparse values), as glTF specifies.
class AccessorReader {
public:
    // maxElements caps any accessor's count (and so what one read allocates).
    AccessorReader(const tinygltf::Model& model, std::size_t maxElements);

    // Number of elements, after checking that the accessor exists.
    std::size_t count(int accessor, const std::string& what) const;
    // Components per element of its type: 1 (SCALAR), 2, 3, 4 (VECn), 4, 9, 16 (MATn).
    int numComponents(int accessor, const std::string& what) const;

    // count * numComponents values, element-major. Normalized integers map to [0, 1] or
    // [-1, 1] as glTF specifies; other integers keep their value. Throws unless the accessor
    // has exactly numComponents per element and one of the allowed component types.
    std::vector<float> readFloats(int accessor, int numComponents, std::uint32_t allowed, const std::string& what) const;
    // The same for unsigned integer data (indices, joints), read exactly.
    std::vector<std::uint32_t> readUints(int accessor, int numComponents, std::uint32_t allowed, const std::string& what) const;

    // The bytes of a buffer view, checked to lie inside its buffer.
    std::span<const std::uint8_t> bufferView(int view, const std::string& what) const;

private:
    template <class T>
    std::vector<T> read(int accessor, int numComponents, std::uint32_t allowed, const std::string& what) const;

    const tinygltf::Model& m_model;
    std::size_t m_maxElements;
};

}  // namespace streak::gltf
