// Shading shared by the GL methods, the GLSL twin of scene/shading.cpp: material albedo with
// the glTF alpha modes, anisotropic texture filtering over a footprint, Phong lighting
// split into what multiplies the albedo and what adds to it.

struct SurfacePoint {
    vec3 position;
    vec3 normal;        // any length
    vec2 uv;
    vec2 duvdx, duvdy;  // uv change one sample spacing right and down
    vec4 vertexColor;
    uint material;
    bool isFrontFacing;
};

// Texture `index` at uv and lod. The loop keeps the sampler index dynamically uniform.
vec4 sampleTexture(int index, vec2 uv, float lod) {
    vec4 texel = vec4(0.0);
    if (isnan(uv.x) || isnan(uv.y)) return texel;
    for (int i = 0; i < MAX_TEXTURES; ++i)
        if (i == index) texel = textureLod(u_textures[i], uv, lod);
    return texel;
}

vec2 textureSizeOf(int index) {
    vec2 size = vec2(1.0);
    for (int i = 0; i < MAX_TEXTURES; ++i)
        if (i == index) size = vec2(textureSize(u_textures[i], 0));
    return size;
}

// footprintEllipse (texture.cpp): the footprint's semi-axes in texels, and the major axis.
struct FootprintEllipse {
    float major, minor;
    vec2 majorAxis;
};

FootprintEllipse footprintEllipse(vec2 a, vec2 b, vec2 d) {
    float p = a.x * a.x + b.x * b.x + d.x * d.x, q = a.x * a.y + b.x * b.y + d.x * d.y, r = a.y * a.y + b.y * b.y + d.y * d.y;
    float mean = 0.5 * (p + r), spread = sqrt(0.25 * (p - r) * (p - r) + q * q);
    FootprintEllipse e;
    e.major = sqrt(max(mean + spread, 0.0));
    e.minor = sqrt(max(mean - spread, 0.0));
    vec2 axis = abs(p - r) + abs(q) == 0.0 ? vec2(1.0, 0.0) : p >= r ? vec2(mean + spread - r, q) : vec2(q, mean + spread - p);
    e.majorAxis = axis * (e.major / length(axis));
    return e;
}

// Texture::sample(uv, TextureFootprint): trilinear taps along the major axis of the ellipse of
// the footprint swept along `sweep`, each at the level of the minor axis (and not below minLod,
// nor level 0): one per width, tapsPerWidth per width along the sweep, at most maxSweptTaps (16
// without a sweep, a GPU's lookup).
vec4 sampleSweptFootprint(int index, vec2 uv, vec2 duvdx, vec2 duvdy, vec2 sweep, float minLod, int maxSweptTaps, float tapsPerWidth) {
    int maxTaps = sweep == vec2(0.0) ? 16 : max(maxSweptTaps, 1);
    vec2 size = textureSizeOf(index);
    FootprintEllipse e = footprintEllipse(duvdx * size, duvdy * size, sweep * size);
    if (isinf(e.major) || isnan(e.major)) return sampleTexture(index, uv, 1000.0);
    float width = max(max(e.minor, e.major / float(maxTaps)), exp2(max(minLod, 0.0)));
    float extraTaps = (max(tapsPerWidth, 1.0) - 1.0) * length(sweep * size);
    int taps = clamp(int(ceil((e.major + extraTaps) / width - 1e-3)), 1, maxTaps);
    float lod = width > 0.0 ? log2(width) : 0.0;
    if (taps == 1) return sampleTexture(index, uv, lod);
    vec2 step = e.majorAxis / size / float(taps);
    vec4 sum = vec4(0.0);
    for (int i = 0; i < taps; ++i) sum += sampleTexture(index, uv + step * (float(i) + 0.5 - 0.5 * float(taps)), lod);
    return sum / float(taps);
}

vec4 sampleFootprint(int index, vec2 uv, vec2 duvdx, vec2 duvdy, float minLod) {
    return sampleSweptFootprint(index, uv, duvdx, duvdy, vec2(0.0), minLod, 16, 1.0);
}

int textureLevelsOf(int index) {
    int levels = 1;
    for (int i = 0; i < MAX_TEXTURES; ++i)
        if (i == index) levels = textureQueryLevels(u_textures[i]);
    return levels;
}

// UvTriangleTest (texture.cpp): whether a tap lies inside a uv triangle, by its barycentrics;
// everything is inside when the triangle is degenerate in uv.
struct UvTriangle {
    bool isActive;
    dvec2 origin, edge1, edge2, row1, row2;
};

UvTriangle uvTriangle(bool isClipped, vec2 corners[3]) {
    UvTriangle t;
    t.isActive = false;
    if (!isClipped) return t;
    t.origin = dvec2(corners[0]);
    t.edge1 = dvec2(corners[1]) - t.origin;
    t.edge2 = dvec2(corners[2]) - t.origin;
    double det = t.edge1.x * t.edge2.y - t.edge1.y * t.edge2.x;
    if (det == 0.0 || isinf(det) || isnan(det)) return t;
    t.row1 = dvec2(t.edge2.y, -t.edge2.x) / det;
    t.row2 = dvec2(-t.edge1.y, t.edge1.x) / det;
    t.isActive = true;
    return t;
}

dvec3 uvBarycentrics(UvTriangle t, vec2 uv) {
    dvec2 d = dvec2(uv) - t.origin;
    double b1 = dot(t.row1, d), b2 = dot(t.row2, d);
    return dvec3(1.0 - b1 - b2, b1, b2);
}

bool isInsideUv(UvTriangle t, vec2 uv) {
    if (!t.isActive) return true;
    dvec3 b = uvBarycentrics(t, uv);
    const double kEdge = -1e-6;  // a tap on an edge belongs to both triangles
    return b.x >= kEdge && b.y >= kEdge && b.z >= kEdge;
}

vec2 heldUv(UvTriangle t, vec2 uv) {
    if (!t.isActive) return uv;
    dvec3 b = uvBarycentrics(t, uv);
    if (!(b.x >= 0.0 && b.y >= 0.0 && b.z >= 0.0)) {
        dvec3 c = max(b, dvec3(0.0));
        double sum = c.x + c.y + c.z;
        b = sum > 0.0 ? c / sum : dvec3(1.0 / 3.0);
    }
    return vec2(t.origin + b.y * t.edge1 + b.z * t.edge2);
}

// Texture::boxGrid: (level, tapsX, tapsY, tapsAlong) for a box lengthX x lengthY texels swept
// along a path pathTexels long: the finest level where the box takes at most a quarter of
// `budget` (kMaxSweptBoxTaps, or exposure::boxBudgetOf's less) taps, the path tapsPerTexel a
// spacing of it (at most maxPathTaps), fewer where box and path together would pass the budget,
// down to two a width of the box's narrower side; on level 0 each axis at least fewestTaps of
// it, within that quarter in all.
const int kMaxSweptBoxTaps = 256;
ivec4 boxGrid(int index, float lengthX, float lengthY, float pathTexels, float tapsPerTexel, int maxPathTaps, ivec2 fewestTaps, int budget) {
    budget = clamp(budget, 4, kMaxSweptBoxTaps);
    int mostAtOnce = budget / 4;
    int maxLevel = textureLevelsOf(index) - 1;
    ivec4 grid = ivec4(maxLevel, 1, 1, 1);
    bool isFinite = !(isinf(lengthX) || isnan(lengthX) || isinf(lengthY) || isnan(lengthY) || isinf(pathTexels) || isnan(pathTexels));
    if (isFinite) {
        maxPathTaps = max(maxPathTaps, 1);
        bool isFound = false;
        for (int l = 0; l <= maxLevel; ++l) {
            float spacing = exp2(float(l));
            // (At most mostAtOnce + 1 an axis, as Texture::boxGrid: no int overflows.)
            int x = max(1, int(min(ceil(lengthX / spacing - 1e-3), float(mostAtOnce + 1))));
            int y = max(1, int(min(ceil(lengthY / spacing - 1e-3), float(mostAtOnce + 1))));
            int t = clamp(int(ceil(min(tapsPerTexel * pathTexels / spacing, float(maxPathTaps)))), 1, maxPathTaps);
            if (!isFound) {
                grid = ivec4(l, x, y, t);
                isFound = x * y <= mostAtOnce;
            }
        }
        grid.y = min(grid.y, mostAtOnce);
        grid.z = min(grid.z, mostAtOnce / grid.y);
        if (grid.x == 0) {
            grid.y = max(grid.y, min(fewestTaps.x, mostAtOnce / grid.z));
            grid.z = max(grid.z, min(fewestTaps.y, mostAtOnce / grid.y));
        }
        int covering = int(ceil(min(2.0 * pathTexels / max(min(lengthX, lengthY), 1e-6), float(maxPathTaps))));
        grid.w = min(grid.w, max(max(1, covering), budget / (grid.y * grid.z)));
    }
    return grid;
}

// Texture::sampleBox on a grid: the mean of bilinear taps over the parallelogram duvdx x duvdy
// around uv, grid.y x grid.z of them at level grid.x; with isClipped only the taps inside the uv
// triangle `corners` count, and `inside` gets their share.
vec4 sampleBox(int index, vec2 uv, vec2 duvdx, vec2 duvdy, ivec4 grid, bool isClipped, vec2 corners[3], out float inside) {
    // One exit, and no break or continue: llvmpipe loses later work of an invocation that left
    // such loops or returned early here.
    inside = 1.0;
    vec4 result = vec4(0.0);
    vec2 size = textureSizeOf(index);
    float lengthX = length(duvdx * size), lengthY = length(duvdy * size);
    int maxLevel = textureLevelsOf(index) - 1;
    bool isUsable = !(isnan(uv.x) || isnan(uv.y));
    bool isFinite = !(isinf(lengthX) || isnan(lengthX) || isinf(lengthY) || isnan(lengthY));
    if (isUsable && !isFinite) result = sampleTexture(index, uv, float(maxLevel));
    if (isUsable && isFinite) {
        int tapsX = grid.y, tapsY = grid.z;
        float lod = float(grid.x);
        UvTriangle clip = uvTriangle(isClipped, corners);
        if (tapsX * tapsY == 1) {
            // One tap: the centre, held to the triangle when it falls outside, all or nothing.
            bool isCentreInside = isInsideUv(clip, uv);
            inside = isCentreInside ? 1.0 : 0.0;
            result = sampleTexture(index, isCentreInside ? uv : heldUv(clip, uv), lod);
        } else {
            vec2 stepX = duvdx / float(tapsX), stepY = duvdy / float(tapsY);
            vec2 origin = uv - 0.5 * (duvdx + duvdy) + 0.5 * (stepX + stepY);
            vec4 sum = vec4(0.0);
            int used = 0;
            for (int j = 0; j < tapsY; ++j)
                for (int i = 0; i < tapsX; ++i) {
                    vec2 tap = origin + stepX * float(i) + stepY * float(j);
                    if (isInsideUv(clip, tap)) {
                        sum += sampleTexture(index, tap, lod);
                        ++used;
                    }
                }
            inside = float(used) / float(tapsX * tapsY);
            // No tap inside (a triangle smaller than their spacing): the centre, held to it.
            result = used > 0 ? sum / float(used) : sampleTexture(index, heldUv(clip, uv), lod);
        }
    }
    return result;
}

// Texture::finestLodOfFootprint: the level of the anisotropic taps.
float finestLodOfFootprint(int index, vec2 duvdx, vec2 duvdy) {
    vec2 size = textureSizeOf(index);
    FootprintEllipse e = footprintEllipse(duvdx * size, duvdy * size, vec2(0.0));
    float width = max(e.minor, e.major / 16.0);
    return width > 0.0 ? log2(width) : 0.0;
}

bool isTranslucentMaterial(uint m) { return materials[m].info.w != 0; }

// Material::alphaOf.
float alphaOf(uint m, float pointAlpha) {
    MaterialData mat = materials[m];
    float opacity = mat.baseColorOpacity.w;
    if (mat.info.y == 1) return opacity * pointAlpha >= mat.phong.z ? 1.0 : 0.0;
    if (mat.info.y == 2) return opacity * pointAlpha;
    return opacity;
}

// materialAlbedo: base colour times texture times vertex colour, and alpha through the mode.
vec4 materialAlbedo(uint m, vec2 uv, vec2 duvdx, vec2 duvdy, vec4 vertexColor) {
    MaterialData mat = materials[m];
    vec4 texel = vec4(1.0);
    if (mat.info.x >= 0) texel = sampleFootprint(mat.info.x, uv, duvdx, duvdy, 0.0);
    return vec4(mat.baseColorOpacity.rgb * texel.rgb * vertexColor.rgb, alphaOf(m, texel.a * vertexColor.a));
}

struct PhongTerms {
    vec3 diffuse;   // times the albedo
    vec3 specular;  // added
};

PhongTerms phongTerms(uint m, vec3 position, vec3 normal, bool isFrontFacing, vec3 eye) {
    float len = length(normal);
    if (!(len > 0.0)) return PhongTerms(u_ambient.rgb, vec3(0.0));
    normal /= len;
    if (!isFrontFacing) normal = -normal;
    float diffuse = max(0.0, dot(normal, u_toLight.xyz));
    PhongTerms terms = PhongTerms(u_ambient.rgb + u_lightColor.rgb * diffuse, vec3(0.0));
    float specular = materials[m].phong.x;
    if (diffuse > 0.0 && specular > 0.0) {
        vec3 toEye = normalize(eye - position);
        vec3 reflected = reflect(-u_toLight.xyz, normal);
        float highlight = pow(max(0.0, dot(reflected, toEye)), materials[m].phong.y);
        terms.specular = u_lightColor.rgb * (specular * highlight);
    }
    return terms;
}

bool isLit() { return u_flags.x == 1; }
bool isNormalPass() { return u_flags.x == 2; }  // ShadingMode::Normal

// shadingNormal: the unit normal a point is shaded with, towards the viewer on a back face.
vec3 shadingNormal(vec3 normal, bool isFrontFacing) {
    float len = length(normal);
    if (!(len > 0.0)) return vec3(0.0);
    return (isFrontFacing ? 1.0 : -1.0) * normal / len;
}

// shadeSurface: the colour and alpha of a point at one instant, seen from `eye` (the normal pass:
// its normal, with the albedo's alpha).
vec4 shadeSurface(SurfacePoint p, vec3 eye) {
    vec4 result = materialAlbedo(p.material, p.uv, p.duvdx, p.duvdy, p.vertexColor);
    if (isLit()) {
        PhongTerms terms = phongTerms(p.material, p.position, p.normal, p.isFrontFacing, eye);
        result.rgb = result.rgb * terms.diffuse + terms.specular;
    } else if (isNormalPass()) {
        result.rgb = shadingNormal(p.normal, p.isFrontFacing);
    }
    return result;
}

// FlatGeometry::surfacePoint: what shading needs from triangle `tri` at one time, given its
// corners then and the barycentrics at the sample and one pixel right and down.
SurfacePoint surfacePoint(uint tri, vec3 corners[3], vec3 cornerNormals[3], vec3 bary, vec3 baryRight, vec3 baryDown,
                          bool isFrontFacing) {
    uvec4 t = triangles[tri];
    SurfacePoint p;
    p.position = bary.x * corners[0] + bary.y * corners[1] + bary.z * corners[2];
    if (meshHasNormals(t.x)) p.normal = bary.x * cornerNormals[0] + bary.y * cornerNormals[1] + bary.z * cornerNormals[2];
    else p.normal = cross(corners[1] - corners[0], corners[2] - corners[0]);
    vec2 uv0 = vertexUv(t.x), uv1 = vertexUv(t.y), uv2 = vertexUv(t.z);
    p.uv = bary.x * uv0 + bary.y * uv1 + bary.z * uv2;
    p.duvdx = (baryRight.x * uv0 + baryRight.y * uv1 + baryRight.z * uv2) - p.uv;
    p.duvdy = (baryDown.x * uv0 + baryDown.y * uv1 + baryDown.z * uv2) - p.uv;
    p.vertexColor = bary.x * vertexColor(t.x) + bary.y * vertexColor(t.y) + bary.z * vertexColor(t.z);
    p.material = t.w & kMaterialMask;
    p.isFrontFacing = isFrontFacing;
    return p;
}
