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

// The texture coordinates at (b1, b2) of the triangle.
vec2 surfaceUv(uint triangle, float b1, float b2) {
    vec4 uv01 = P.triangleUvs.v[2u * triangle];
    vec2 uv2 = P.triangleUvs.v[2u * triangle + 1u].xy;
    return (1.0f - b1 - b2) * uv01.xy + b1 * uv01.zw + b2 * uv2;
}

// The vertex colour (COLOR_0) at (b1, b2) of the triangle, which multiplies its albedo.
vec3 vertexColor(uint triangle, float b1, float b2) {
    if (P.triangleInfo.v[triangle].vertexColors == 0u) {
        return vec3(1.0f);
    }
    return (1.0f - b1 - b2) * P.triangleColors.v[3u * triangle].rgb + b1 * P.triangleColors.v[3u * triangle + 1u].rgb +
           b2 * P.triangleColors.v[3u * triangle + 2u].rgb;
}

// The triangle's front (counter-clockwise) normal, of length twice its area: as
// `largest` times `scaled`, whose largest component is 1, since the squares of a
// triangle's cross product leave float range once its edges pass about 4e9.
struct ScaledNormal {
    vec3 scaled;
    float largest;
};

ScaledNormal scaledNormal(vec3 v0, vec3 v1, vec3 v2) {
    vec3 n = cross(v1 - v0, v2 - v0);
    float largest = maxComponent(abs(n));
    return ScaledNormal(n / largest, largest);
}

SurfacePoint surfacePoint(uint triangle, float b1, float b2) {
    vec3 v0 = P.triangleVertices.v[3u * triangle].xyz;
    vec3 v1 = P.triangleVertices.v[3u * triangle + 1u].xyz;
    vec3 v2 = P.triangleVertices.v[3u * triangle + 2u].xyz;
    ScaledNormal n = scaledNormal(v0, v1, v2);
    float scaledLength = length(n.scaled);
    float doubleArea = n.largest * scaledLength;
    GpuTriangleInfo info = P.triangleInfo.v[triangle];
    SurfacePoint sp;
    sp.position = v0 + b1 * (v1 - v0) + b2 * (v2 - v0);
    sp.normal = n.scaled / scaledLength;
    sp.uv = surfaceUv(triangle, b1, b2);
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

// The medium on the near side of a medium boundary with medium `interior` inside and
// `outside` around it, met at `facing` (the ray's direction dotted with the triangle's
// outward normal, at any scale): `carried` where the ray runs along it.
uint mediumBeforeBoundary(uint interior, uint outside, float facing, uint carried) {
    return facing > 0.0f ? interior : facing < 0.0f ? outside : carried;
}

// The medium a ray is in as it meets `triangle` (kNoHit: as it leaves the scene), as that
// end of its segment tells: a medium boundary met from inside is in its medium, one met
// from outside in the medium around it, and a ray that leaves the scene is in the scene
// medium. At an opaque surface (or one the ray runs along) it is `carried`, the medium
// the ray set out in. Boundaries are closed and wound outwards (medium_boundaries.h), so
// this is the carried medium wherever that is right; it differs where a crossing at a
// boundary's edge took the wrong side (docs/design.md, "Rays leaving a surface").
uint mediumAtSegmentEnd(uint triangle, vec3 direction, uint carried) {
    if (triangle == kNoHit) {
        return P.sceneMedium;
    }
    GpuTriangleInfo info = P.triangleInfo.v[triangle];
    int interior = P.materials.v[info.material].interiorMedium;
    if (interior < 0) {
        return carried;
    }
    vec3 normal = scaledNormal(P.triangleVertices.v[3u * triangle].xyz, P.triangleVertices.v[3u * triangle + 1u].xyz,
                               P.triangleVertices.v[3u * triangle + 2u].xyz).scaled;
    return mediumBeforeBoundary(uint(interior), info.outsideMedium, dot(direction, normal), carried);
}

// How a material looks up one of its textures: the uv transform's rows and the wrap
// modes along u and v.
struct TextureMap {
    int texture;               // index into the texture table, -1: none
    vec4 uRow;
    vec4 vRow;
    uvec2 wrap;
};

TextureMap baseColorMap(GpuMaterial m) {
    return TextureMap(m.baseColorTexture, m.baseColorUvRows[0], m.baseColorUvRows[1], m.wrap.xy);
}

TextureMap emissionMap(GpuMaterial m) {
    return TextureMap(m.emissionTexture, m.emissionUvRows[0], m.emissionUvRows[1], m.wrap.zw);
}

// A texture coordinate brought into one period of its wrap mode in float, before it is
// scaled to texels: far from [0, 1) (|uv| up to float's range is valid glTF) a texel
// coordinate would leave int range. Where float holds only whole periods (beyond about
// 2^24, or a transform's product beyond float's range) this is the corner, as at 0.
float foldCoordinate(float x, uint wrap) {
    if (wrap == kWrapClampToEdge) {
        // Beyond [-1, 2] every texel of the footprint clamps to the same edge anyway.
        return isnan(x) ? 0.0f : clamp(x, -1.0f, 2.0f);
    }
    if (isinf(x) || isnan(x)) {
        return 0.0f;
    }
    return wrap == kWrapMirroredRepeat ? x - 2.0f * floor(0.5f * x) : fract(x);
}

// Texel index i of n along one axis, wrapped (GLSL leaves % of negative operands
// undefined, hence floor division).
int wrapTexel(int i, int n, uint wrap) {
    if (wrap == kWrapClampToEdge) {
        return clamp(i, 0, n - 1);
    }
    if (wrap == kWrapMirroredRepeat) {
        int k = i - 2 * n * int(floor(float(i) / float(2 * n)));
        return k < n ? k : 2 * n - 1 - k;
    }
    return i - n * int(floor(float(i) / float(n)));
}

// The four texels a bilinear lookup blends, and their weights; uv (0, 0) is the top-left
// corner of the image. The adjoint spreads a texture value's gradient over the same
// texels with the same weights.
struct BilinearFootprint {
    uint texel[4];  // indices into P.texels
    vec4 weight;
};

BilinearFootprint bilinearFootprint(TextureMap map, vec2 uv) {
    GpuTexture tex = P.textures.v[map.texture];
    vec3 uv1 = vec3(uv, 1.0f);
    vec2 folded = vec2(foldCoordinate(dot(map.uRow.xyz, uv1), map.wrap.x),
                       foldCoordinate(dot(map.vRow.xyz, uv1), map.wrap.y));
    vec2 st = folded * vec2(tex.width, tex.height) - 0.5f;
    vec2 cell = floor(st);
    vec2 f = st - cell;
    ivec2 size = ivec2(tex.width, tex.height);
    ivec2 c0 = ivec2(cell);
    BilinearFootprint footprint;
    for (int corner = 0; corner < 4; ++corner) {
        ivec2 offset = ivec2(corner & 1, corner >> 1);
        ivec2 c = ivec2(wrapTexel(c0.x + offset.x, size.x, map.wrap.x), wrapTexel(c0.y + offset.y, size.y, map.wrap.y));
        // Clamped too, so that no rounding can read outside the texture's texels.
        c = clamp(c, ivec2(0), size - 1);
        footprint.texel[corner] = tex.firstTexel + uint(c.y) * tex.width + uint(c.x);
        footprint.weight[corner] = (offset.x == 1 ? f.x : 1.0f - f.x) * (offset.y == 1 ? f.y : 1.0f - f.y);
    }
    return footprint;
}

vec3 textureLookup(TextureMap map, vec2 uv) {
    BilinearFootprint footprint = bilinearFootprint(map, uv);
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
    return m.emissionTexture >= 0 ? textureLookup(emissionMap(m), uv) : vec3(1.0f);
}

// Radiance leaving the surface towards `toViewer`.
vec3 emittedRadiance(GpuMaterial m, vec3 normal, vec2 uv, vec3 toViewer) {
    return m.emission.rgb * emissionPerUnit(m, normal, uv, toViewer);
}

// The base colour texture's value (1 without a texture): albedo = baseColor * this.
vec3 baseColorTexture(GpuMaterial m, vec2 uv) {
    return m.baseColorTexture >= 0 ? textureLookup(baseColorMap(m), uv) : vec3(1.0f);
}

vec3 sigmaT(GpuMedium medium) {
    return medium.sigma_a + medium.sigma_s;
}

#endif
