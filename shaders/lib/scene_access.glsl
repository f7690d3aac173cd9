// Reading the scene: triangle geometry, materials with their textures, media.
#ifndef VKDR_SCENE_ACCESS_GLSL
#define VKDR_SCENE_ACCESS_GLSL
#include "constants.glsl"

struct SurfacePoint {
    vec3 position;
    vec3 normal;      // geometric, unit, on the front (counter-clockwise) side
    vec2 uv;
    float area;       // of the triangle
    uint material;
    uint outsideMedium;
};

SurfacePoint surfacePoint(uint triangle, float b1, float b2) {
    vec3 v0 = P.triangleVertices.v[3u * triangle].xyz;
    vec3 v1 = P.triangleVertices.v[3u * triangle + 1u].xyz;
    vec3 v2 = P.triangleVertices.v[3u * triangle + 2u].xyz;
    vec4 uv01 = P.triangleUvs.v[2u * triangle];
    vec2 uv2 = P.triangleUvs.v[2u * triangle + 1u].xy;
    vec3 n = cross(v1 - v0, v2 - v0);
    // Scaled by its largest component first: the squares of a triangle's cross product
    // leave float range once its edges pass about 4e9.
    float largest = maxComponent(abs(n));
    vec3 scaled = n / largest;
    float scaledLength = length(scaled);
    float doubleArea = largest * scaledLength;
    GpuTriangleInfo info = P.triangleInfo.v[triangle];
    SurfacePoint sp;
    sp.position = v0 + b1 * (v1 - v0) + b2 * (v2 - v0);
    sp.normal = scaled / scaledLength;
    sp.uv = (1.0f - b1 - b2) * uv01.xy + b1 * uv01.zw + b2 * uv2;
    sp.area = 0.5f * doubleArea;
    sp.material = info.material;
    sp.outsideMedium = info.outsideMedium;
    return sp;
}

// The interpolated shading normal at (b1, b2), turned to the side of `facing` (the
// geometric normal on the viewer's side); `facing` itself where the mesh has no normals.
vec3 shadingNormal(uint triangle, float b1, float b2, vec3 facing) {
    vec3 n = (1.0f - b1 - b2) * P.triangleNormals.v[3u * triangle].xyz +
             b1 * P.triangleNormals.v[3u * triangle + 1u].xyz + b2 * P.triangleNormals.v[3u * triangle + 2u].xyz;
    float length2 = dot(n, n);
    if (!(length2 > 0.0f)) {
        return facing;
    }
    n *= inversesqrt(length2);
    return dot(n, facing) < 0.0f ? -n : n;
}

// Whether the triangle blocks light: anything but a pass-through medium boundary.
bool isOpaque(uint triangle) {
    return P.materials.v[P.triangleInfo.v[triangle].material].interiorMedium < 0;
}

// i mod n for negative i too (GLSL leaves % of negative operands undefined).
ivec2 wrapRepeat(ivec2 i, ivec2 n) {
    return i - n * ivec2(floor(vec2(i) / vec2(n)));
}

// The four texels a bilinear lookup with repeat wrapping blends, and their weights;
// uv (0, 0) is the top-left corner of the image. The adjoint spreads a texture value's
// gradient over the same texels with the same weights.
struct BilinearFootprint {
    uint texel[4];  // indices into P.texels
    vec4 weight;
};

BilinearFootprint bilinearFootprint(int textureIndex, vec2 uv) {
    GpuTexture tex = P.textures.v[textureIndex];
    // Repeat wrapping in float first: far from [0, 1) (|uv| up to float's range is valid
    // glTF) the texel coordinate would leave int range.
    vec2 st = fract(uv) * vec2(tex.width, tex.height) - 0.5f;
    vec2 cell = floor(st);
    vec2 f = st - cell;
    ivec2 size = ivec2(tex.width, tex.height);
    ivec2 c0 = ivec2(cell);
    BilinearFootprint footprint;
    for (int corner = 0; corner < 4; ++corner) {
        ivec2 offset = ivec2(corner & 1, corner >> 1);
        // Clamped too: a coordinate interpolated beyond float range is NaN after fract.
        ivec2 c = clamp(wrapRepeat(c0 + offset, size), ivec2(0), size - 1);
        footprint.texel[corner] = tex.firstTexel + uint(c.y) * tex.width + uint(c.x);
        footprint.weight[corner] = (offset.x == 1 ? f.x : 1.0f - f.x) * (offset.y == 1 ? f.y : 1.0f - f.y);
    }
    return footprint;
}

vec3 textureLookup(int textureIndex, vec2 uv) {
    BilinearFootprint footprint = bilinearFootprint(textureIndex, uv);
    vec3 sum = vec3(0.0f);
    for (int corner = 0; corner < 4; ++corner) {
        sum += footprint.weight[corner] * P.texels.v[footprint.texel[corner]].rgb;
    }
    return sum;
}

// Emitted radiance per unit of the material's emission parameter towards `toViewer`:
// the emission texture, or 0 behind a one-sided emitter.
vec3 emissionPerUnit(GpuMaterial m, vec3 normal, vec2 uv, vec3 toViewer) {
    if (m.doubleSided == 0u && dot(normal, toViewer) <= 0.0f) {
        return vec3(0.0f);
    }
    return m.emissionTexture >= 0 ? textureLookup(m.emissionTexture, uv) : vec3(1.0f);
}

// Radiance leaving the surface towards `toViewer`.
vec3 emittedRadiance(GpuMaterial m, vec3 normal, vec2 uv, vec3 toViewer) {
    return m.emission.rgb * emissionPerUnit(m, normal, uv, toViewer);
}

// The base colour texture's value (1 without a texture): albedo = baseColor * this.
vec3 baseColorTexture(GpuMaterial m, vec2 uv) {
    return m.baseColorTexture >= 0 ? textureLookup(m.baseColorTexture, uv) : vec3(1.0f);
}

vec3 sigmaT(GpuMedium medium) {
    return medium.sigma_a + medium.sigma_s;
}

#endif
