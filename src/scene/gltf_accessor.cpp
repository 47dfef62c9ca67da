#include "scene/gltf_accessor.h"

#include "util/error.h"

#include "scene/gltf_document.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <type_traits>

namespace streak::gltf {

namespace {

// The bit and byte size of a glTF component type; 0 for types glTF 2.0 does not allow
// (including 5124, signed int).
std::uint32_t componentBit(int componentType) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return kFloat;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return kUnsignedByte;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return kUnsignedShort;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return kUnsignedInt;
    case TINYGLTF_COMPONENT_TYPE_BYTE: return kByte;
    case TINYGLTF_COMPONENT_TYPE_SHORT: return kShort;
    default: return 0;
    }
}

std::size_t componentSize(std::uint32_t bit) {
    if (bit == kFloat || bit == kUnsignedInt) return 4;
    if (bit == kUnsignedShort || bit == kShort) return 2;
    return 1;
}

const char* typeName(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "an unknown type";
    }
}

int typeFor(int numComponents) {
    switch (numComponents) {
    case 1: return TINYGLTF_TYPE_SCALAR;
    case 2: return TINYGLTF_TYPE_VEC2;
    case 3: return TINYGLTF_TYPE_VEC3;
    case 4: return TINYGLTF_TYPE_VEC4;
    case 16: return TINYGLTF_TYPE_MAT4;
    default: return -1;
    }
}

// One component at p (unaligned), as float (normalized per glTF 3.11) or exact unsigned.
template <class Out, class In>
Out convert(const std::uint8_t* p, bool normalized) {
    In value;
    std::memcpy(&value, p, sizeof(In));
    if constexpr (std::is_floating_point_v<Out>) {
        if constexpr (std::is_integral_v<In>) {
            if (normalized) {
                constexpr float kMax = float(std::numeric_limits<In>::max());
                return std::max(float(value) / kMax, -1.0f);
            }
        }
        return Out(value);
    } else {
        return Out(value);
    }
}

template <class Out>
Out component(const std::uint8_t* p, std::uint32_t bit, bool normalized) {
    switch (bit) {
    case kFloat: return convert<Out, float>(p, normalized);
    case kUnsignedByte: return convert<Out, std::uint8_t>(p, normalized);
    case kUnsignedShort: return convert<Out, std::uint16_t>(p, normalized);
    case kUnsignedInt: return convert<Out, std::uint32_t>(p, normalized);
    case kByte: return convert<Out, std::int8_t>(p, normalized);
    case kShort:
    default: return convert<Out, std::int16_t>(p, normalized);
    }
}

// `length` bytes at `offset` fit in `size` bytes, without overflow.
bool fits(std::uint64_t offset, std::uint64_t length, std::uint64_t size) { return offset <= size && length <= size - offset; }

}  // namespace

AccessorReader::AccessorReader(const tinygltf::Model& model, std::size_t maxElements) : m_model(model), m_maxElements(maxElements) {}

std::size_t AccessorReader::count(int accessor, const std::string& what) const {
    if (accessor < 0 || std::size_t(accessor) >= m_model.accessors.size())
        throw Error(what + ": accessor " + std::to_string(accessor) + " does not exist");
    return m_model.accessors[std::size_t(accessor)].count;
}

int AccessorReader::numComponents(int accessor, const std::string& what) const {
    count(accessor, what);
    const int n = tinygltf::GetNumComponentsInType(std::uint32_t(m_model.accessors[std::size_t(accessor)].type));
    if (n <= 0) throw Error(what + " (accessor " + std::to_string(accessor) + "): unknown element type");
    return n;
}

std::span<const std::uint8_t> AccessorReader::bufferView(int view, const std::string& what) const {
    if (view < 0 || std::size_t(view) >= m_model.bufferViews.size())
        throw Error(what + ": buffer view " + std::to_string(view) + " does not exist");
    const tinygltf::BufferView& bv = m_model.bufferViews[std::size_t(view)];
    if (bv.buffer < 0 || std::size_t(bv.buffer) >= m_model.buffers.size())
        throw Error(what + ": buffer view " + std::to_string(view) + " names buffer " + std::to_string(bv.buffer) + ", which does not exist");
    const std::vector<unsigned char>& data = m_model.buffers[std::size_t(bv.buffer)].data;
    if (!fits(bv.byteOffset, bv.byteLength, data.size()))
        throw Error(what + ": buffer view " + std::to_string(view) + " (bytes " + std::to_string(bv.byteOffset) + " + " +
                    std::to_string(bv.byteLength) + ") exceeds buffer " + std::to_string(bv.buffer) + " (" + std::to_string(data.size()) +
                    " bytes)");
    return {data.data() + bv.byteOffset, bv.byteLength};
}

template <class T>
std::vector<T> AccessorReader::read(int index, int numComponents, std::uint32_t allowed, const std::string& what) const {
    const std::size_t count = this->count(index, what);
    const tinygltf::Accessor& accessor = m_model.accessors[std::size_t(index)];
    const std::string where = what + " (accessor " + std::to_string(index) + ")";
    if (accessor.type != typeFor(numComponents))
        throw Error(where + ": element type is " + typeName(accessor.type) + ", expected " + typeName(typeFor(numComponents)));
    const std::uint32_t bit = componentBit(accessor.componentType);
    if (bit == 0 || (bit & allowed) == 0)
        throw Error(where + ": component type " + std::to_string(accessor.componentType) + " is not allowed here");
    if (count == 0) throw Error(where + ": count is 0");
    if (count > m_maxElements)
        throw Error(where + ": count " + std::to_string(count) + " is over the limit of " + std::to_string(m_maxElements));
    const std::size_t n = std::size_t(numComponents);
    const std::size_t size = componentSize(bit), elementSize = n * size;

    std::vector<T> out(count * n, T(0));
    if (accessor.bufferView >= 0) {
        const std::span<const std::uint8_t> view = bufferView(accessor.bufferView, where);
        const std::size_t declaredStride = m_model.bufferViews[std::size_t(accessor.bufferView)].byteStride;
        const std::size_t stride = declaredStride == 0 ? elementSize : declaredStride;
        if (stride < elementSize || stride > 252 || stride % size != 0)
            throw Error(where + ": byteStride " + std::to_string(declaredStride) + " does not fit elements of " + std::to_string(elementSize) +
                        " bytes");
        // count <= maxElements and stride <= 252, so the span cannot overflow 64 bits.
        const std::uint64_t span = std::uint64_t(count - 1) * stride + elementSize;
        if (!fits(accessor.byteOffset, span, view.size()))
            throw Error(where + ": byteOffset " + std::to_string(accessor.byteOffset) + " + " + std::to_string(count) + " elements of stride " +
                        std::to_string(stride) + " exceed buffer view " + std::to_string(accessor.bufferView) + " (" +
                        std::to_string(view.size()) + " bytes)");
        const std::uint8_t* base = view.data() + accessor.byteOffset;
        for (std::size_t e = 0; e < count; ++e)
            for (std::size_t c = 0; c < n; ++c) out[e * n + c] = component<T>(base + e * stride + c * size, bit, accessor.normalized);
    }

    if (accessor.sparse.isSparse) {
        const auto& sparse = accessor.sparse;
        if (sparse.count <= 0 || std::size_t(sparse.count) > count)
            throw Error(where + ": sparse count " + std::to_string(sparse.count) + " is not in [1, " + std::to_string(count) + "]");
        const std::size_t numSparse = std::size_t(sparse.count);
        const std::uint32_t indexBit = componentBit(sparse.indices.componentType);
        if ((indexBit & kUnsignedInts) == 0) throw Error(where + ": sparse indices must be unsigned byte, short or int");
        const std::size_t indexSize = componentSize(indexBit);
        const std::span<const std::uint8_t> indexView = bufferView(sparse.indices.bufferView, where + " sparse indices");
        const std::span<const std::uint8_t> valueView = bufferView(sparse.values.bufferView, where + " sparse values");
        if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0 ||
            !fits(std::uint64_t(sparse.indices.byteOffset), std::uint64_t(numSparse) * indexSize, indexView.size()) ||
            !fits(std::uint64_t(sparse.values.byteOffset), std::uint64_t(numSparse) * elementSize, valueView.size()))
            throw Error(where + ": sparse indices or values exceed their buffer views");
        const std::uint8_t* indices = indexView.data() + sparse.indices.byteOffset;
        const std::uint8_t* values = valueView.data() + sparse.values.byteOffset;
        for (std::size_t s = 0; s < numSparse; ++s) {
            const std::uint32_t target = component<std::uint32_t>(indices + s * indexSize, indexBit, false);
            if (target >= count)
                throw Error(where + ": sparse index " + std::to_string(target) + " is out of range (count " + std::to_string(count) + ")");
            for (std::size_t c = 0; c < n; ++c)
                out[std::size_t(target) * n + c] = component<T>(values + s * elementSize + c * size, bit, accessor.normalized);
        }
    }
    return out;
}

std::vector<float> AccessorReader::readFloats(int accessor, int numComponents, std::uint32_t allowed, const std::string& what) const {
    return read<float>(accessor, numComponents, allowed, what);
}

std::vector<std::uint32_t> AccessorReader::readUints(int accessor, int numComponents, std::uint32_t allowed, const std::string& what) const {
    return read<std::uint32_t>(accessor, numComponents, allowed & kUnsignedInts, what);
}

}  // namespace streak::gltf
