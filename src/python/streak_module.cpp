// The Python module `streak`: the public API (include/streak/streak.h) with numpy arrays in
// and out. Errors are streak.Error with the command line's one-line message.

#include <streak/streak.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <optional>
#include <string>
#include <type_traits>

namespace py = pybind11;
namespace sk = streak::api;

namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

// A float array of the given rank whose last dimension is `last` (0: any), or Error naming it.
FloatArray floats(const py::handle& object, const char* name, int rank, py::ssize_t last, const char* shape) {
    FloatArray a;
    try {
        a = FloatArray::ensure(object);
    } catch (const py::error_already_set&) {
    }
    if (!a || a.ndim() != rank || (last > 0 && a.shape(rank - 1) != last))
        throw streak::Error(std::string(name) + " must be a float array of shape " + shape);
    return a;
}

std::vector<float> flat(const FloatArray& a) { return std::vector<float>(a.data(), a.data() + a.size()); }

std::array<float, 3> triple(const py::handle& object, const char* name) {
    const FloatArray a = floats(object, name, 1, 3, "(3,)");
    return {a.at(0), a.at(1), a.at(2)};
}

// H x W x 3, or H x W x 4 with alpha (colour premultiplied by it).
py::array_t<float> arrayOf(const sk::Image& image) {
    const py::ssize_t channels = image.hasAlpha() ? 4 : 3;
    py::array_t<float> out({py::ssize_t(image.height), py::ssize_t(image.width), channels});
    float* data = out.mutable_data();
    const std::size_t n = std::size_t(image.width) * std::size_t(image.height);
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t c = 0; c < 3; ++c) data[i * std::size_t(channels) + c] = image.rgb[3 * i + c];
        if (image.hasAlpha()) data[4 * i + 3] = image.alpha[i];
    }
    return out;
}

// The image and its passes: {'image': arrayOf, channel name: H x W, 'metadata': {key: text}}.
py::dict layersOf(const sk::Image& image) {
    py::dict out;
    out["image"] = arrayOf(image);
    for (const sk::Image::Channel& c : image.channels) {
        py::array_t<float> values({py::ssize_t(image.height), py::ssize_t(image.width)});
        std::copy(c.values.begin(), c.values.end(), values.mutable_data());
        out[py::str(c.name)] = values;
    }
    py::dict metadata;
    for (const auto& [key, value] : image.metadata) metadata[py::str(key)] = value;
    out["metadata"] = metadata;
    return out;
}

// A deep image as {'counts': H x W uint32, 'samples': N x 6 float32 (Z, ZBack, R, G, B, A),
// pixel by pixel, front to back}, and a region's 'origin' (x, y) and 'frame' (width, height).
constexpr std::size_t kDeepColumns = sizeof(sk::DeepImage::Sample) / sizeof(float);
static_assert(kDeepColumns == 6);

py::dict deepOf(const sk::DeepImage& deep) {
    py::dict out;
    py::array_t<std::uint32_t> counts({py::ssize_t(deep.height), py::ssize_t(deep.width)});
    std::copy(deep.counts.begin(), deep.counts.end(), counts.mutable_data());
    py::array_t<float> samples({py::ssize_t(deep.samples.size()), py::ssize_t(kDeepColumns)});
    if (!deep.samples.empty()) std::memcpy(samples.mutable_data(), deep.samples.data(), deep.samples.size() * sizeof(sk::DeepImage::Sample));
    out["counts"] = counts;
    out["samples"] = samples;
    if (deep.isRegion()) out["origin"] = py::make_tuple(deep.x, deep.y), out["frame"] = py::make_tuple(deep.frameWidth, deep.frameHeight);
    return out;
}

sk::DeepImage deepOf(const py::dict& in) {
    if (!in.contains("counts") || !in.contains("samples")) throw streak::Error("deep image: a dict {'counts': (H, W), 'samples': (N, 6)} expected");
    py::array_t<long long, py::array::c_style | py::array::forcecast> counts;
    const py::array given = py::array::ensure(in["counts"]);
    if (given && (given.dtype().kind() == 'i' || given.dtype().kind() == 'u')) {
        try {
            counts = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(given);
        } catch (const py::error_already_set&) {
        }
    }
    if (!counts || counts.ndim() != 2) throw streak::Error("deep image: 'counts' must be an integer array of shape (H, W)");
    const FloatArray samples = floats(in["samples"], "deep image 'samples'", 2, py::ssize_t(kDeepColumns), "(N, 6): Z, ZBack, R, G, B, A");
    sk::DeepImage deep;
    deep.height = int(counts.shape(0)), deep.width = int(counts.shape(1));
    for (py::ssize_t i = 0; i < counts.size(); ++i) {
        const long long c = counts.data()[i];
        if (c < 0 || c > 0xffffffffLL) throw streak::Error("deep image: counts must be in [0, 2^32)");
        deep.counts.push_back(std::uint32_t(c));
    }
    deep.samples.resize(std::size_t(samples.shape(0)));
    // Sample is six floats, trivially copyable (its default member initializers only make it
    // non-trivial to construct), so the rows copy as bytes.
    static_assert(std::is_trivially_copyable_v<sk::DeepImage::Sample> && sizeof(sk::DeepImage::Sample) == 6 * sizeof(float));
    if (!deep.samples.empty()) std::memcpy(static_cast<void*>(deep.samples.data()), samples.data(), deep.samples.size() * sizeof(sk::DeepImage::Sample));
    if (in.contains("origin") != in.contains("frame")) throw streak::Error("deep image: a region has both 'origin' (x, y) and 'frame' (width, height)");
    if (in.contains("origin")) {
        try {
            const auto origin = in["origin"].cast<std::pair<int, int>>(), frame = in["frame"].cast<std::pair<int, int>>();
            deep.x = origin.first, deep.y = origin.second, deep.frameWidth = frame.first, deep.frameHeight = frame.second;
        } catch (const py::cast_error&) {
            throw streak::Error("deep image: 'origin' and 'frame' must be pairs of integers");
        }
    }
    return deep;
}

sk::Image imageOf(const py::handle& object, const char* name) {
    const FloatArray a = floats(object, name, 3, 0, "(H, W, 3) or (H, W, 4)");
    if (a.shape(2) != 3 && a.shape(2) != 4) throw streak::Error(std::string(name) + " must be a float array of shape (H, W, 3) or (H, W, 4)");
    sk::Image image;
    image.height = int(a.shape(0)), image.width = int(a.shape(1));
    if (a.shape(2) == 3) {
        image.rgb = flat(a);
        return image;
    }
    const std::size_t n = std::size_t(a.shape(0)) * std::size_t(a.shape(1));
    for (std::size_t i = 0; i < n; ++i) {
        image.rgb.insert(image.rgb.end(), a.data() + 4 * i, a.data() + 4 * i + 3);
        image.alpha.push_back(a.data()[4 * i + 3]);
    }
    return image;
}

sk::Camera cameraOf(const py::dict& camera) {
    sk::Camera c;
    for (const auto& [key, value] : camera) {
        const std::string k = py::str(key);
        if (k == "position") c.open.position = triple(value, "camera['position']");
        else if (k == "target") c.open.target = triple(value, "camera['target']");
        else if (k == "up") c.open.up = triple(value, "camera['up']");
        else if (k == "fov") c.verticalFovDegrees = value.cast<float>();
        else if (k == "znear") c.zNear = value.cast<float>();
        else if (k != "position_end" && k != "target_end" && k != "up_end")
            throw streak::Error("camera: unknown key '" + k + "' (position, target, up, fov, znear, position_end, target_end, up_end)");
    }
    c.close = c.open;
    if (camera.contains("position_end")) c.close.position = triple(camera["position_end"], "camera['position_end']");
    if (camera.contains("target_end")) c.close.target = triple(camera["target_end"], "camera['target_end']");
    if (camera.contains("up_end")) c.close.up = triple(camera["up_end"], "camera['up_end']");
    return c;
}

// One mesh from its arrays; `where` prefixes the errors ("" for from_arrays' one mesh).
sk::Mesh meshOf(const py::handle& keys, const py::handle& indices, const py::object& uvs, const py::object& normals, const std::string& where) {
    const FloatArray k = floats(keys, (where + "keys").c_str(), 3, 3, "(K, V, 3): K key poses of V vertices");
    sk::Mesh mesh;
    mesh.keys = int(k.shape(0));
    mesh.positions = flat(k);
    py::array_t<long long, py::array::c_style | py::array::forcecast> tri;
    try {
        tri = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(indices);
    } catch (const py::error_already_set&) {
    }
    if (!tri || tri.ndim() != 2 || tri.shape(1) != 3) throw streak::Error(where + "indices must be an integer array of shape (T, 3)");
    mesh.indices.reserve(std::size_t(tri.size()));
    for (py::ssize_t i = 0; i < tri.size(); ++i) {
        const long long v = tri.data()[i];
        if (v < 0 || v >= k.shape(1))
            throw streak::Error(where + "indices: index " + std::to_string(v) + " is out of range (" + std::to_string(k.shape(1)) + " vertices)");
        mesh.indices.push_back(std::uint32_t(v));
    }
    if (!uvs.is_none()) {
        const FloatArray u = floats(uvs, (where + "uvs").c_str(), 2, 2, "(V, 2)");
        if (u.shape(0) != k.shape(1)) throw streak::Error(where + "uvs must have one row per vertex (" + std::to_string(k.shape(1)) + ")");
        mesh.uvs = flat(u);
    }
    if (!normals.is_none()) {
        const FloatArray n = floats(normals, (where + "normals").c_str(), 3, 3, "(K, V, 3), as keys");
        if (n.shape(0) != k.shape(0) || n.shape(1) != k.shape(1)) throw streak::Error(where + "normals must have the shape of keys");
        mesh.normals = flat(n);
    }
    return mesh;
}

// H x W x 4 or 3: uint8 sRGB colour (alpha linear), or float linear.
sk::Texture textureOf(const py::handle& texture, const std::string& name) {
    py::array t;
    try {
        t = py::array::ensure(texture);
    } catch (const py::error_already_set&) {
    }
    if (!t || t.ndim() != 3 || (t.shape(2) != 4 && t.shape(2) != 3)) throw streak::Error(name + " must be an array of shape (H, W, 4) or (H, W, 3)");
    sk::Texture tex;
    tex.height = int(t.shape(0)), tex.width = int(t.shape(1));
    const bool isBytes = t.dtype().is(py::dtype::of<std::uint8_t>());
    const py::ssize_t texels = t.shape(0) * t.shape(1), channels = t.shape(2);
    if (isBytes) {
        const auto b = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>::ensure(t);
        tex.rgba8.reserve(std::size_t(4 * texels));
        for (py::ssize_t i = 0; i < texels; ++i)
            for (int c = 0; c < 4; ++c) tex.rgba8.push_back(c < channels ? b.data()[i * channels + c] : 255);
    } else {
        const FloatArray f = FloatArray::ensure(t);
        tex.rgbaFloat.reserve(std::size_t(4 * texels));
        for (py::ssize_t i = 0; i < texels; ++i)
            for (int c = 0; c < 4; ++c) tex.rgbaFloat.push_back(c < channels ? f.data()[i * channels + c] : 1.0f);
    }
    return tex;
}

std::array<float, 3> backgroundOf(const py::object& background) {
    return background.is_none() ? std::array<float, 3>{0, 0, 0} : triple(background, "background");
}

sk::Scene fromArrays(const py::handle& keys, const py::handle& indices, const py::object& uvs, const py::object& normals,
                     const py::object& texture, const py::dict& camera, const py::object& baseColor, bool doubleSided,
                     const py::object& background) {
    const sk::Mesh mesh = meshOf(keys, indices, uvs, normals, "");
    std::vector<sk::Texture> textures;
    sk::Material material;
    material.doubleSided = doubleSided;
    if (!baseColor.is_none()) material.baseColor = triple(baseColor, "base_color");
    if (!texture.is_none()) {
        textures.push_back(textureOf(texture, "texture"));
        material.texture = 0;
    }
    return sk::Scene::fromArrays({mesh}, {material}, cameraOf(camera), textures, backgroundOf(background));
}

// Many meshes, each a dict {keys, indices, uvs, normals, material, name}; materials dicts
// {base_color, texture, opacity, double_sided, specular, shininess, name}; textures arrays.
sk::Scene fromMeshes(const py::list& meshes, const py::list& materials, const py::list& textures, const py::dict& camera,
                     const py::object& background, const py::object& frameCameras) {
    std::vector<sk::Mesh> outMeshes;
    std::vector<std::vector<float>> framePositions;  // with frame_cameras: each mesh's at the 3 frames
    for (std::size_t i = 0; i < meshes.size(); ++i) {
        const std::string where = "meshes[" + std::to_string(i) + "]: ";
        if (!py::isinstance<py::dict>(meshes[i])) throw streak::Error(where + "must be a dict {keys, indices, uvs, normals, material, name}");
        const py::dict d = meshes[i].cast<py::dict>();
        for (const auto& [key, value] : d) {
            const std::string k = py::str(key);
            if (k != "keys" && k != "indices" && k != "uvs" && k != "normals" && k != "material" && k != "name" && k != "frame_positions")
                throw streak::Error(where + "unknown key '" + k + "' (keys, indices, uvs, normals, material, name, frame_positions)");
        }
        if (!d.contains("keys") || !d.contains("indices")) throw streak::Error(where + "needs 'keys' and 'indices'");
        auto get = [&](const char* key) { return d.contains(key) ? py::object(d[key]) : py::object(py::none()); };
        sk::Mesh mesh = meshOf(d["keys"], d["indices"], get("uvs"), get("normals"), where);
        if (d.contains("material")) mesh.material = d["material"].cast<int>();
        if (d.contains("name")) mesh.name = d["name"].cast<std::string>();
        if (d.contains("frame_positions") != !frameCameras.is_none())
            throw streak::Error(where + "'frame_positions' and frame_cameras come together (the vector pass's frames)");
        if (d.contains("frame_positions")) {
            const FloatArray f = floats(d["frame_positions"], (where + "frame_positions").c_str(), 3, 3, "(3, V, 3): its vertices at the frames F - 1, F, F + 1");
            if (f.shape(0) != 3) throw streak::Error(where + "frame_positions must be of shape (3, V, 3): its vertices at the frames F - 1, F, F + 1");
            framePositions.push_back(flat(f));
        }
        outMeshes.push_back(std::move(mesh));
    }
    std::vector<sk::Material> outMaterials;
    for (std::size_t i = 0; i < materials.size(); ++i) {
        const std::string where = "materials[" + std::to_string(i) + "]: ";
        if (!py::isinstance<py::dict>(materials[i])) throw streak::Error(where + "must be a dict");
        sk::Material m;
        for (const auto& [key, value] : materials[i].cast<py::dict>()) {
            const std::string k = py::str(key);
            if (k == "base_color") m.baseColor = triple(value, (where + "base_color").c_str());
            else if (k == "texture") m.texture = value.is_none() ? -1 : value.cast<int>();
            else if (k == "opacity") m.opacity = value.cast<float>();
            else if (k == "double_sided") m.doubleSided = value.cast<bool>();
            else if (k == "specular") m.specular = value.cast<float>();
            else if (k == "shininess") m.shininess = value.cast<float>();
            else if (k == "name") m.name = value.cast<std::string>();
            else throw streak::Error(where + "unknown key '" + k + "' (base_color, texture, opacity, double_sided, specular, shininess, name)");
        }
        outMaterials.push_back(std::move(m));
    }
    if (outMaterials.empty()) outMaterials.emplace_back();
    std::vector<sk::Texture> outTextures;
    for (std::size_t i = 0; i < textures.size(); ++i) outTextures.push_back(textureOf(textures[i], "textures[" + std::to_string(i) + "]"));
    const sk::Scene scene = sk::Scene::fromArrays(outMeshes, outMaterials, cameraOf(camera), outTextures, backgroundOf(background));
    if (frameCameras.is_none()) return scene;
    const py::list cameras = frameCameras.cast<py::list>();
    if (cameras.size() != 3) throw streak::Error("frame_cameras must be 3 camera dicts: at the frames F - 1, F and F + 1");
    std::array<sk::Camera, 3> frames;
    for (std::size_t k = 0; k < 3; ++k) frames[k] = cameraOf(cameras[k].cast<py::dict>());
    return scene.withFrames(framePositions, frames);
}

sk::Scene sceneOf(const py::handle& scene) {
    if (py::isinstance<py::str>(scene)) return sk::Scene::load(scene.cast<std::string>());
    return scene.cast<sk::Scene>();
}

}  // namespace

PYBIND11_MODULE(streak, m) {
    m.doc() = "streak: analytic motion blur of moving and deforming triangle meshes (linear light, shutter t in [0, 1])";
    const auto error = py::register_exception<streak::Error>(m, "Error", PyExc_ValueError);
    py::register_exception<streak::Cancelled>(m, "Cancelled", error.ptr());

    py::class_<sk::Scene>(m, "Scene", "A validated scene: streak.Scene.load(spec) or streak.Scene.from_arrays(...)")
        .def_static(
            "load",
            [](const std::string& spec, double frame, double shutter, double fps, const std::string& animation, const std::string& position,
               int width, int height, int motionKeys, const std::string& motionCurve, int motionCurveOrder, double keyTolerance,
               const std::string& pointCache, const std::string& pointCacheMesh, const std::string& pointCacheSpace, const std::string& velocityUnit,
               bool sequenceInterpolate) {
                sk::LoadOptions o;
                o.frame = frame, o.shutterFrames = shutter, o.fps = fps, o.animation = animation, o.shutterPosition = position;
                o.width = width, o.height = height;
                o.motionKeys = motionKeys, o.motionCurve = motionCurve, o.motionCurveOrder = motionCurveOrder, o.keyTolerancePixels = keyTolerance;
                o.pointCache = pointCache, o.pointCacheMesh = pointCacheMesh, o.pointCacheSpace = pointCacheSpace, o.velocityUnit = velocityUnit;
                o.sequenceInterpolate = sequenceInterpolate;
                return sk::Scene::load(spec, o);
            },
            py::arg("spec"), py::arg("frame") = 0.0, py::arg("shutter") = 0.5, py::arg("fps") = 24.0, py::arg("animation") = "",
            py::arg("shutter_position") = "start", py::arg("width") = 1024, py::arg("height") = 768, py::arg("motion_keys") = 0,
            py::arg("motion_curve") = "linear", py::arg("motion_curve_order") = 2, py::arg("key_tolerance") = 0.125,
            py::arg("point_cache") = "", py::arg("point_cache_mesh") = "", py::arg("point_cache_space") = "object", py::arg("velocity_unit") = "second", py::arg("sequence_interpolate") = false,
            "builtin:NAME[?k=v&...], a .gltf/.glb file, or an .obj/.ply mesh or numbered sequence (mesh_%04d.ply); glTF time in frames and motion keys as on the command line "
            "(motion_keys 0: chosen by key_tolerance; motion_curve bezier without motion_keys: Bezier pieces of motion_curve_order); "
            "point_cache: a .pc2 or .mdd moving the mesh point_cache_mesh (or the only one), in object or world point_cache_space; velocity_unit: second or frame, of _VELOCITY and PLY vx vy vz")
        .def_static("from_arrays", &fromArrays, py::arg("keys"), py::arg("indices"), py::arg("uvs") = py::none(),
                    py::arg("normals") = py::none(), py::arg("texture") = py::none(), py::arg("camera") = py::dict(),
                    py::arg("base_color") = py::none(), py::arg("double_sided") = true, py::arg("background") = py::none(),
                    "one mesh: keys (K, V, 3) key poses over the shutter, indices (T, 3), uvs (V, 2), normals (K, V, 3), "
                    "texture (H, W, 4|3) uint8 sRGB or float linear; camera {position, target, up, fov, znear, position_end, target_end, up_end}")
        .def_static("from_meshes", &fromMeshes, py::arg("meshes"), py::arg("materials") = py::list(), py::arg("textures") = py::list(),
                    py::arg("camera") = py::dict(), py::arg("background") = py::none(), py::arg("frame_cameras") = py::none(),
                    "many meshes: meshes [{keys (K, V, 3), indices (T, 3), uvs (V, 2), normals (K, V, 3), material (index), name}], "
                    "materials [{base_color, texture (index), opacity, double_sided, specular, shininess, name}] (none: one white), "
                    "textures [(H, W, 4|3) uint8 sRGB or float linear]; camera as from_arrays; names are the Cryptomatte names; "
                    "for the vector pass, frame_cameras [3 camera dicts] and each mesh's frame_positions (3, V, 3): the camera and its "
                    "vertices standing still at the frames F - 1, F and F + 1 around the shutter's")
        .def("with_shutter", [](const sk::Scene& s, const std::string& curve, float rolling) { return s.withShutter({curve, rolling}); },
             py::arg("curve") = "box", py::arg("rolling") = 1.0f)
        .def_property_readonly("num_triangles", &sk::Scene::numTriangles)
        .def_property_readonly("skipped_triangles", &sk::Scene::skippedTriangles);

    m.def(
        "render",
        [](const py::handle& scene, const std::string& method, int width, int height, int aa, bool unlit, std::uint64_t seed,
           const std::map<std::string, std::string>& options, bool stats, int memoryBudgetMB, const std::optional<std::array<int, 4>>& region,
           bool transparent, const std::vector<std::string>& passes, int cryptomatteRanks, const py::object& progress,
           const py::object& cancel, int threads, bool deep, int deepSamples, float adaptive, float adaptiveFull) -> py::object {
            sk::RenderSettings s;
            s.method = method, s.width = width, s.height = height, s.aa = aa, s.unlit = unlit, s.seed = seed, s.options = options;
            s.transparent = transparent;
            s.passes = passes, s.cryptomatteRanks = cryptomatteRanks;
            s.deep = deep, s.deepSamples = deepSamples;
            s.adaptive = adaptive, s.adaptiveFull = adaptiveFull;
            s.memoryBudgetMB = memoryBudgetMB;
            s.threads = threads;
            if (region) s.region = sk::Region{(*region)[0], (*region)[1], (*region)[2], (*region)[3]};
            const sk::Scene sc = sceneOf(scene);
            // The callbacks run on this thread (the API's promise) with the GIL taken back; an
            // exception they raise stops the render and is raised again here.
            std::optional<py::error_already_set> raised;
            auto guarded = [&](auto call) {
                if (raised) return true;
                py::gil_scoped_acquire gil;
                try {
                    return bool(call());
                } catch (py::error_already_set& e) {
                    raised.emplace(std::move(e));
                    return true;
                }
            };
            std::function<void(double)> onProgress;
            std::function<bool()> onCancel;
            if (!progress.is_none()) onProgress = [&](double f) { guarded([&] { progress(f); return false; }); };
            if (!cancel.is_none()) onCancel = [&] { return guarded([&] { return py::bool_(cancel()).cast<bool>(); }); };
            if (!progress.is_none() && cancel.is_none()) onCancel = [&] { return bool(raised); };
            sk::RenderResult result;
            try {
                py::gil_scoped_release release;
                result = sk::Renderer(s).render(sc, onProgress, onCancel);
            } catch (const streak::Cancelled&) {
                if (raised) throw std::move(*raised);
                throw;
            }
            if (raised) throw std::move(*raised);  // raised by the last callback, after which nothing asked
            py::object image = passes.empty() && !deep ? py::object(arrayOf(result.image)) : py::object(layersOf(result.image));
            if (result.deep) image["deep"] = deepOf(*result.deep);
            if (stats) return py::make_tuple(image, py::module_::import("json").attr("loads")(result.stats.json()));
            return image;
        },
        py::arg("scene"), py::arg("method") = "motion-path", py::arg("width") = 1024, py::arg("height") = 768, py::arg("aa") = 1,
        py::arg("unlit") = false, py::arg("seed") = 0, py::arg("options") = std::map<std::string, std::string>(), py::arg("stats") = false,
        py::arg("memory_budget_mb") = sk::kDefaultMemoryBudgetMB, py::arg("region") = py::none(), py::arg("transparent") = false,
        py::arg("passes") = std::vector<std::string>(), py::arg("cryptomatte_ranks") = 6, py::arg("progress") = py::none(),
        py::arg("cancel") = py::none(), py::arg("threads") = 0, py::arg("deep") = false, py::arg("deep_samples") = 16, py::arg("adaptive") = 0.0f,
        py::arg("adaptive_full") = 0.0f,
        "render a scene (streak.Scene or spec string): an H x W x 3 float32 array, linear light (with stats=True: (image, stats dict)); "
        "adaptive: a threshold (0: off) for adaptive anti-aliasing, one sample per pixel and aa x aa where a pixel and a neighbour differ by more "
        "than it in sRGB colour or coverage (motion-path, analytic, higher-order); adaptive_full: a refined pixel whose largest difference is at "
        "most it takes half the samples a side (at least 2), the rest aa x aa (0: three times adaptive); "
        "memory_budget_mb: what the exact methods' tile lists keep within; region (x0, y0, x1, y1): only the pixels [x0, x1) x [y0, y1), "
        "an (y1 - y0) x (x1 - x0) x 3 array equal to that slice of the whole image; transparent: a background of alpha 0, "
        "an H x W x 4 array whose alpha is each pixel's exact coverage and whose colour is premultiplied by it; "
        "passes ['depth', 'object_id', 'material_id', 'albedo', 'normal', 'vector']: a dict {'image': the array, channel name: H x W array, 'metadata': {...}} "
        "(Z, Z.min, CryptoObject00.r, ...; cryptomatte_ranks pairs); progress(fraction) is called as the render goes, and "
        "cancel() with it: once cancel returns True the render stops and raises streak.Cancelled (both on the calling thread); "
        "threads: worker threads (0: every core); deep: the dict also holds 'deep', the deep image {'counts': H x W uint32, "
        "'samples': N x 6 float32 (Z, ZBack, R, G, B, A), pixel by pixel front to back}, at most deep_samples surface layers a pixel "
        "(write_deep_image writes it)");
    m.def("methods", [] {
        py::list out;
        for (const sk::Method& method : sk::methods()) out.append(py::make_tuple(method.name, method.description));
        return out;
    }, "[(name, description)] of every method");
    m.def("compare", [](const py::handle& a, const py::handle& b, float threshold) {
        const sk::Comparison c = sk::compare(imageOf(a, "a"), imageOf(b, "b"), threshold);
        py::dict out;
        out["psnr"] = c.psnr, out["ssim"] = c.ssim;
        out["foreground_psnr"] = c.foregroundPsnr, out["foreground_pixels"] = c.foregroundPixels;
        return out;
    }, py::arg("a"), py::arg("b"), py::arg("foreground_threshold") = 2.0f / 255.0f,
    "{'psnr': dB, 'ssim', 'foreground_psnr', 'foreground_pixels'} of two H x W x 3 images in display space "
    "(foreground: where a channel of either is above the threshold)");
    m.def("write_image", [](const py::handle& image, const std::string& path) { sk::writeImage(imageOf(image, "image"), path); },
          py::arg("image"), py::arg("path"), ".png (sRGB 8-bit) or .exr (linear float)");
    m.def("write_deep_image", [](const py::dict& deep, const std::string& path) { sk::writeDeepImage(deepOf(deep), path); }, py::arg("deep"),
          py::arg("path"), "a deep image (render(..., deep=True)['deep']) as a deep scanline EXR: R G B A Z ZBack, tidy");
    m.def("read_deep_image", [](const std::string& path) { return deepOf(sk::readDeepImage(path)); }, py::arg("path"),
          "a deep scanline EXR with R G B A Z ZBack: {'counts': H x W, 'samples': N x 6 (Z, ZBack, R, G, B, A)}");
    m.def("read_image", [](const std::string& path) { return arrayOf(sk::readImage(path)); }, py::arg("path"));
    m.def("read_layers", [](const std::string& path) { return layersOf(sk::readImage(path)); }, py::arg("path"),
          "an image file with its passes: {'image': H x W x 3|4, channel name: H x W, 'metadata': {...}}");
    m.def("compare_passes", [](const std::string& a, const std::string& b) {
        py::list out;
        for (const sk::PassComparison& c : sk::comparePasses(sk::readImage(a), sk::readImage(b))) {
            py::dict row;
            row["pass"] = c.pass, row["rms"] = c.rms, row["max"] = c.maxError, row["pixels"] = c.pixels;
            out.append(row);
        }
        return out;
    }, py::arg("a"), py::arg("b"),
    "[{'pass', 'rms', 'max', 'pixels'}] for the passes two image files both have: alpha, each channel, each Cryptomatte name's matte");
    m.def("cryptomatte_key", &sk::cryptomatteKey, py::arg("layer_name"),
          "the metadata key of a Cryptomatte layer name ('ViewLayer.CryptoObject'): cryptomatte/<key>/name, ...");
    m.def("cryptomatte_matte", [](const std::string& path, const std::string& type, const std::string& name) {
        const sk::Image image = sk::readImage(path);
        const std::vector<float> matte = sk::cryptomatteMatte(image, type, name);
        py::array_t<float> out({py::ssize_t(image.height), py::ssize_t(image.width)});
        std::copy(matte.begin(), matte.end(), out.mutable_data());
        return out;
    }, py::arg("path"), py::arg("type"), py::arg("name"),
    "the H x W matte of object or material `name` in an EXR's Cryptomatte type `type` ('CryptoObject', 'CryptoMaterial')");
}
