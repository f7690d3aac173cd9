// Structs and constants shared by the C++ host and the GLSL stages, included by both
// so a layout is written once. GLSL sees buffer references; C++ sees device addresses
// (uint64_t). Every struct is std430-compatible and pinned with static_asserts on the
// host (src/render/device_layout.cpp).
#ifndef VKDR_DEVICE_TYPES_H
#define VKDR_DEVICE_TYPES_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace vkdr::gpu {
using vec4 = glm::vec4;
using vec3 = glm::vec3;
using uvec4 = glm::uvec4;
using ivec4 = glm::ivec4;
using uint = uint32_t;
#define VKDR_BUFFER(Type) uint64_t
// The host's stand-ins for the GLSL buffer reference types below: the bytes of one
// element, which size the per-path arrays.
struct Vec4Buffer { static constexpr uint32_t kElementBytes = 16; };
struct UVec4Buffer { static constexpr uint32_t kElementBytes = 16; };
struct Vec4PerChannelBuffer { static constexpr uint32_t kElementBytes = 48; };
struct UintBuffer { static constexpr uint32_t kElementBytes = 4; };
struct FloatBuffer { static constexpr uint32_t kElementBytes = 4; };
struct Vec2Buffer { static constexpr uint32_t kElementBytes = 8; };
struct Int64Buffer { static constexpr uint32_t kElementBytes = 8; };
#else
#define VKDR_BUFFER(Type) Type
#endif

// Workgroup size of every stage that walks a queue or the path slots.
const uint kWorkgroupSize = 64;

// Path slot value of PathState.hit.w when the ray left the scene.
const uint kNoHit = 0xffffffffu;
// Medium index for vacuum.
const uint kNoMediumIndex = 0xffffffffu;

// Kinds of vertex a medium_sample stage hands to shade.
const uint kVertexSurface = 0u;
const uint kVertexMedium = 1u;
// Tracking through a density grid reached its step bound at this point, which the path
// passes through without scattering to continue in the next segment (grid_tracking.glsl).
const uint kVertexPause = 2u;

// Sample streams (RenderParams.firstStream, rng.glsl): images draw from streams 0 and 1
// (the halves of a split gradient estimate), paths replayed independently of any image
// from kReplayStream (such a replay is never split in halves).
const uint kImageStream = 0u;
const uint kReplayStream = 2u;

// Loss kinds (RenderParams.lossKind).
const uint kLossL2 = 0u;
const uint kLossL1 = 1u;
// The image the loss stage compares with the target (PassConstants.lossImage): the
// film, or the film less the copy in filmBaseline (the samples added since the copy),
// or both halves of a render whose film stage also summed the samples below
// RenderParams.splitSample into filmBaseline: each half's dLoss/dI is taken at the
// other half's image (imageAdjoint), and the loss at the whole film.
const uint kLossImageFilm = 0u;
const uint kLossImageFilmMinusBaseline = 1u;
const uint kLossImageHalves = 2u;

// The kinds of parameter whose gradients the adjoint stages add, by bit (1 << kind), in
// the order of ParameterKind (src/scene/parameter_kinds.h); the adjoint pipelines are
// compiled for a set of them (kGradientKinds, shaders/lib/stage_common.glsl).
const uint kGradientKindSigmaA = 0u;
const uint kGradientKindSigmaS = 1u;
const uint kGradientKindG = 2u;
const uint kGradientKindBaseColor = 3u;
const uint kGradientKindBaseColorTexture = 4u;
const uint kGradientKindEmission = 5u;
const uint kGradientKindLightIntensity = 6u;
const uint kGradientKindDensity = 7u;
const uint kGradientKindMediumEmission = 8u;
const uint kGradientKindEmissionGrid = 9u;
const uint kGradientKindAlbedoGrid = 10u;
const uint kEveryGradientKind = 0x7ffu;

// Derivative-mode targets of the adjoint pass (shaders/lib/adjoint.glsl): the kinds of
// parameter whose zero-valued factors it follows, where their gradients are wanted.
// A target is its kind | the parameter's index << kTargetIndexShift.
const uint kTargetNone = 0u;
const uint kTargetMediumScattering = 1u;  // sigma_s of a medium
const uint kTargetBaseColor = 2u;         // base colour of a material (factor or texels)
const uint kTargetDensityPoint = 3u;      // a density grid's voxels around one point (densityTargetPoint)
const uint kTargetAlbedoPoint = 4u;       // an albedo grid's voxels around a point (albedoTargetPoints)
const uint kTargetIndexShift = 3u;

// Where each parameter's gradient sits among its medium's kMediumGradientStride floats.
const uint kMediumGradientSigmaA = 0u;  // rgb
const uint kMediumGradientSigmaS = 3u;  // rgb
const uint kMediumGradientG = 6u;       // one value
// rgb: a gradient with respect to sigma_t = sigma_a + sigma_s, when both are wanted, is
// summed here once; gradient_values.comp reads it as part of each of the two. Beside g,
// so that a stage adds both with one addition (flushMediumGradients in adjoint.glsl).
const uint kMediumGradientSigmaT = 7u;
const uint kMediumGradientEmission = 10u;  // rgb
const uint kMediumGradientStride = 13u;
// A base colour, emission or texel gradient: rgb.
const uint kColorGradientStride = 3u;

// Gradients and the loss are summed as fixed-point numbers (shaders/lib/fixed_point.glsl),
// so that a sum has the same bits whatever order its terms arrive in: kFixedPointWords
// signed 64-bit words, word k weighing 2^(32 k + kFixedPointLowestBit), then one word of
// kFixedPoint* flags. Terms are held from 2^-96 (smaller ones are dropped, 20 orders of
// magnitude below the smallest per-path term a float image gives) up to the largest
// float, which fills the low 32 bits of word 6: word 7 and every word's upper bits hold
// the carries of a sum.
const uint kFixedPointWords = 8u;
const int kFixedPointLowestBit = -96;
const uint kFixedPointFlagsWord = kFixedPointWords;
const uint kFixedPointWordsPerSum = kFixedPointWords + 1u;
const uint kFixedPointNaN = 1u;               // a term was NaN
const uint kFixedPointPositiveOverflow = 2u;  // a term was +inf, or the sum outgrew the words
const uint kFixedPointNegativeOverflow = 4u;  // the same for -inf

// The medium, base colour and emission gradients have kGradientCopies copies, a
// RenderParams.<accumulator>CopyStride apart: a subgroup adds to the copy of its index
// modulo kGradientCopies, so that fewer subgroups contend for one address (atomics on
// one address serialise on a GPU), and the host sums the copies. Texel gradients spread
// over the texels already and have one copy (a copy stride of 0). Strides count sums.
const uint kGradientCopies = 32u;
const uint kGradientCopyAlignment = 4u;  // sums: copies start 192 bytes apart

// Per-path state, one element per path slot, each quantity in an array of its own
// (structure of arrays): X(name, buffer type), then what it holds. This line is the
// whole declaration: the RenderParams address, the host's Buffer in PathBuffers, its
// allocation, its share of the bytes per path and its upload follow from it
// (src/render/path_buffers.h). Arrays of every render:
#define VKDR_PATH_ARRAYS(X) \
    X(rayOrigin, Vec4Buffer)          /* xyz: segment start; w: the triangle it leaves (uint bits) */ \
    X(rayDirection, Vec4Buffer)       /* xyz, unit length */ \
    X(beta, Vec4Buffer)               /* rgb path throughput / pdf */ \
    X(radiance, Vec4Buffer)           /* rgb radiance gathered so far; L_rem in the adjoint pass */ \
    X(radianceRounding, Vec4Buffer)   /* rgb: what rounding radiance to floats left out (compensated_sum.glsl) */ \
    X(misVertex, Vec4Buffer)          /* xyz: last scattering vertex; w: its sampling pdf (0: no MIS) */ \
    X(hit, Vec4Buffer)                /* x: t, y: b1, z: b2, w: triangle (uint bits) or kNoHit */ \
    X(pathInfo, UVec4Buffer)          /* x: pixel, y: sample, z: depth, w: segment */ \
    X(vertexInfo, UVec4Buffer)        /* x: current medium, y: vertex kind */ \
    X(shadowOrigin, Vec4Buffer)       /* xyz: where it starts; w: its length to the light */ \
    X(shadowDirection, Vec4Buffer)    /* xyz; w: medium at the origin (uint bits) */ \
    X(shadowContribution, Vec4Buffer) /* rgb: unoccluded next-event contribution; w: the segment (uint bits) */ \
    X(shadowEnds, Vec4Buffer)         /* x, y: the triangles it leaves and ends on (uint bits); z: its lead-out */

// Arrays of the adjoint pass only (AdjointBuffers), allocated when gradients are enabled.
#define VKDR_ADJOINT_PATH_ARRAYS(X) \
    X(pendingFactor, Vec4Buffer)          /* rgb d log f / d theta of the last scattering factor */ \
    X(adjointState, UVec4Buffer)          /* see AdjointState in adjoint.glsl */ \
    X(surfaceHit, Vec4Buffer)             /* the last surface vertex's hit: (-, b1, b2, triangle bits) */ \
    X(shadowScatterGradient, Vec4Buffer)  /* rgb dC/dalbedo (surface); w: d log phase / dg (medium) */ \
    X(shadowEmissionGradient, Vec4Buffer) /* rgb dC/demission; w: the emitter (uint bits, see kPunctualEmitter) */ \
    X(shadowVertex, UVec4Buffer)          /* x: vertex kind, y: material or medium index, z: derivative channels */ \
    X(densityTargetPoint, Vec4Buffer)     /* xyz: index coordinates of a kTargetDensityPoint's point */ \
    X(albedoTargetPoints, Vec4PerChannelBuffer) /* per channel, xyz: the point of its kTargetAlbedoPoint */

// The adjoint pass's gradient accumulators: X(name, SceneGradients field (host), sums
// per item, copies, items (AdjointBuffers' count of them)). Each line declares the
// RenderParams address and copy stride, the host's GradientCopies, its clearing, its
// read-back and the sum of its copies into SceneGradients.
#define VKDR_GRADIENT_ACCUMULATORS(X) \
    X(mediumGradients, media, kMediumGradientStride, kGradientCopies, mediumCount) \
    X(baseColorGradients, baseColors, kColorGradientStride, kGradientCopies, materialCount) \
    X(emissionGradients, emissions, kColorGradientStride, kGradientCopies, materialCount) \
    X(lightGradients, lights, kColorGradientStride, kGradientCopies, punctualLightCount) \
    X(texelGradients, texels, kColorGradientStride, 1u, texelCount) /* in the order of RenderParams.texels */ \
    X(densityGradients, densities, 1u, 1u, voxelCount) /* in the order of RenderParams.gridValues */

#ifdef __cplusplus
// The host's names for the accumulators, in the order of the list, and their layouts.
#define VKDR_ACCUMULATOR_ENUMERATOR(name, ...) name,
enum class GradientAccumulator { VKDR_GRADIENT_ACCUMULATORS(VKDR_ACCUMULATOR_ENUMERATOR) };
#undef VKDR_ACCUMULATOR_ENUMERATOR
struct GradientAccumulatorLayout {
    uint sumsPerItem;
    uint copies;
};
#define VKDR_ACCUMULATOR_LAYOUT(name, field, floats, copies, items) GradientAccumulatorLayout{floats, copies},
inline constexpr GradientAccumulatorLayout kGradientAccumulatorLayouts[] = {
    VKDR_GRADIENT_ACCUMULATORS(VKDR_ACCUMULATOR_LAYOUT)};
#undef VKDR_ACCUMULATOR_LAYOUT
constexpr GradientAccumulatorLayout layoutOf(GradientAccumulator accumulator) {
    return kGradientAccumulatorLayouts[static_cast<uint>(accumulator)];
}
#endif

// Queues: indices into QueueCounters.counts and .dispatch.
const uint kQueueRays0 = 0u;   // rays to trace this segment (double-buffered with kQueueRays1)
const uint kQueueRays1 = 1u;
const uint kQueueShade = 2u;   // medium vertices at the front, surface vertices at the back
const uint kQueueShadow = 3u;  // next-event shadow rays
const uint kQueueCount = 4u;
// The two ends of a queue's array (queues.glsl): the ray queues hold rays in a medium at
// the front and rays in vacuum at the back, the shade queue medium vertices at the
// front and surface vertices at the back.
const uint kFrontEnd = 0u;
const uint kBackEnd = 1u;

// Texture wrap modes (TextureWrap in src/scene/scene.h).
const uint kWrapRepeat = 0u;
const uint kWrapClampToEdge = 1u;
const uint kWrapMirroredRepeat = 2u;

struct GpuMaterial {
    vec4 baseColor;            // rgb: Lambertian albedo factor
    vec4 emission;             // rgb: emitted radiance
    int baseColorTexture;      // index into the texture table, -1: none
    int emissionTexture;       // index into the texture table, -1: none
    int interiorMedium;        // >= 0: pass-through boundary around media[i]
    uint doubleSided;          // 1: emits from both sides
    // Each texture's uv transform: u' = dot(xyz of row 0, (u, v, 1)), v' = with row 1.
    vec4 baseColorUvRows[2];
    vec4 emissionUvRows[2];
    uvec4 wrap;                // kWrap*: base colour along u, along v; emission along u, along v
};

// A punctual light as placed in the scene (Scene::lightPlacements, with its light's values).
const uint kLightPoint = 0u;
const uint kLightSpot = 1u;
const uint kLightDirectional = 2u;
struct GpuPunctualLight {
    vec3 position;
    uint type;                 // kLightPoint, kLightSpot or kLightDirectional
    vec3 direction;            // unit, where it shines
    float cosOuterCone;        // spot only
    vec3 intensity;            // rgb color x intensity
    float cosInnerCone;        // spot only
    uint light;                // index into Scene::punctualLights: where its gradient goes
    float pmf;                 // probability of choosing it for next-event estimation
    uint pad0, pad1;
};

// Entries of RenderParams.lightSources, and the emitter of a next-event estimate: an
// emissive triangle's index, or kPunctualEmitter | a GpuPunctualLight's index.
const uint kPunctualEmitter = 0x80000000u;

struct GpuMedium {
    vec3 sigma_a;              // absorption, per unit length (times the density, in a grid medium)
    float g;                   // Henyey-Greenstein anisotropy
    vec3 sigma_s;              // scattering, per unit length (times the density, in a grid medium)
    uint densityGrid;          // index into RenderParams.densityGrids, kNoDensityGrid: homogeneous
    vec3 emission;             // radiance emitted per unit length (times the density, in a grid medium,
                               // or the emission grid's value where there is one)
    uint emissionGrid;         // index into RenderParams.densityGrids, kNoDensityGrid: none
    uint albedoGrid;           // index into RenderParams.densityGrids (an RGB grid), kNoDensityGrid: none
    uint padding[3];           // std430 rounds the struct to 16 bytes
};

const uint kNoDensityGrid = 0xffffffffu;
// Edge of a majorant cell, in voxels: each cell holds the largest density the trilinear
// lookup takes anywhere inside it (src/render/majorant_grid.h).
const int kMajorantCellVoxels = 8;
// Tentative collisions and majorant cells that free flight, and the transmittance
// tracking of one ray (all its grid segments together), walk at most, below lavapipe's
// silent loop cap. Free flight that reaches its bound pauses (kVertexPause) and goes on
// in the next segment; transmittance tracking that reaches its bound is counted
// (QueueCountersData.truncatedTracking) and the render refused.
const uint kMaxFreeFlightSteps = 1024u;
const uint kMaxTransmittanceSteps = 8192u;
// Where a gradient pass differentiates the density, free flight also accepts tentative
// collisions where the density is 0, so that a path can scatter there and find the
// gradient of adding scattering (docs/density-grids.md, "Where the density is 0"): as if
// the density there were c = kDefensiveCollisionsPerCrossing / (L max(sigma_t)), L the
// diagonal of the box the density reaches (GpuDensityGrid.tracking.x holds 1 / L), so
// that a ray crossing the grid meets about that many such collisions at most, and at
// most kDefensiveCollisionShare of a cell's majorant. An empty cell is walked with the
// majorant c / kDefensiveCollisionShare.
const float kDefensiveCollisionsPerCrossing = 0.25f;
const float kDefensiveCollisionShare = 0.25f;

// A density grid as placed in the scene: its voxels (a dense box, x fastest) in
// RenderParams.gridValues and its majorant cells in RenderParams.gridMajorants.
struct GpuDensityGrid {
    vec4 worldToIndex[3];      // rows of the 3x4 matrix from world to index coordinates
    ivec4 firstVoxel;          // xyz: index coordinates of the box's first voxel; w: its offset in gridValues
    ivec4 size;                // xyz: voxels along each axis; w: offset of the first cell in gridMajorants
    ivec4 majorantOrigin;      // xyz: index coordinates of the lower corner of cell (0, 0, 0)
    ivec4 majorantCells;       // xyz: cells along each axis (0 for an albedo grid); w: values per voxel
    vec4 tracking;             // x: 1 / the world length of the diagonal of the box the density
                               // reaches (kDefensiveCollisionsPerCrossing); yzw: 0
};

struct GpuTexture {
    uint firstTexel;           // offset into the texel buffer
    uint width;
    uint height;
    uint pad;
};

// Per triangle, in BVH leaf order (the GPU never sees the file's triangle order).
struct GpuTriangleInfo {
    uint material;             // index into materials
    uint outsideMedium;        // boundaries: medium on the front side; kNoMediumIndex: vacuum
    float lightPmf;            // probability of choosing this triangle for next-event estimation
    uint vertexColors;         // 1: triangleColors holds its vertices' colours; 0: white
};

struct GpuCamera {
    vec4 cameraToWorld[3];     // rows of the 3x4 matrix
    float tanHalfFovY;
    float aspect;              // width / height
    uint width;                // pixels
    uint height;
    uint medium;               // medium containing the camera, kNoMediumIndex: vacuum
    float orthographicHalfHeight;  // > 0: rays start across the camera's XY plane, parallel
    uint pad1, pad2;
};

// Dispatch sizes written on the device so stages can be launched indirectly.
struct DispatchArgs {
    uint x, y, z, pad;
};

struct QueueCountersData {
    uint counts[kQueueCount];
    DispatchArgs dispatch[kQueueCount];
    // The two ends (kFrontEnd, kBackEnd) of the queue queue_prepare sized last, for the
    // stages that have a pipeline for each end (medium_sample, shade).
    DispatchArgs ends[2];
    uint truncatedLoops;   // > 0: a loop hit its iteration bound (or lavapipe's silent cap)
    uint truncatedPaths;   // paths ended by the segment limit rather than by the estimator
    uint raysTraced;       // closest-hit and shadow rays since the host last cleared it
    uint backCounts[kQueueCount];  // the items at each queue's back; counts[] those at its front
    uint truncatedTracking;  // rays whose transmittance tracking through a density grid hit its step bound
};

#ifndef __cplusplus
layout(buffer_reference, std430, buffer_reference_align = 16) buffer Vec4Buffer { vec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer UVec4Buffer { uvec4 v[]; };
// Three vec4s per path slot, one per channel: v[slot * 3 + c].
layout(buffer_reference, std430, buffer_reference_align = 16) buffer Vec4PerChannelBuffer { vec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer UintBuffer { uint v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer FloatBuffer { float v[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) buffer Vec2Buffer { vec2 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) buffer Int64Buffer { int64_t v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer MaterialBuffer { GpuMaterial v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer MediumBuffer { GpuMedium v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer DensityGridBuffer { GpuDensityGrid v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer TextureBuffer { GpuTexture v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer PunctualLightBuffer { GpuPunctualLight v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer TriangleInfoBuffer { GpuTriangleInfo v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer QueueCounters { QueueCountersData c; };
#endif

// Everything a stage reads: the scene and the path state, by device address.
struct RenderParams {
    GpuCamera camera;
    vec4 background;                                // rgb radiance of escaped rays
    // Scene
    VKDR_BUFFER(Vec4Buffer) triangleVertices;       // 3 per triangle (BVH order), xyz
    VKDR_BUFFER(Vec4Buffer) triangleUvs;            // 2 per triangle: (uv0, uv1), (uv2, -)
    VKDR_BUFFER(Vec4Buffer) triangleNormals;        // 3 per triangle, xyz: unit shading normals, or 0: flat
    VKDR_BUFFER(Vec4Buffer) triangleColors;         // 3 per triangle, rgb: vertex colours (one entry where
                                                    // the scene has none)
    VKDR_BUFFER(TriangleInfoBuffer) triangleInfo;
    VKDR_BUFFER(Vec4Buffer) bvhNodes;               // 2 per node, see src/bvh/bvh.h
    VKDR_BUFFER(MaterialBuffer) materials;
    VKDR_BUFFER(MediumBuffer) media;
    VKDR_BUFFER(TextureBuffer) textures;
    VKDR_BUFFER(Vec4Buffer) texels;                 // linear RGBA
    VKDR_BUFFER(UintBuffer) lightSources;           // emissive triangles (BVH-order index) and punctual
                                                    // lights (kPunctualEmitter | index into punctualLights)
    VKDR_BUFFER(FloatBuffer) lightCdf;              // lightCount + 1 entries, 0 .. 1
    VKDR_BUFFER(PunctualLightBuffer) punctualLights;
    VKDR_BUFFER(DensityGridBuffer) densityGrids;
    VKDR_BUFFER(FloatBuffer) gridValues;            // every grid's voxels, one grid after another
    VKDR_BUFFER(FloatBuffer) gridMajorants;         // every grid's majorant cells, one grid after another
    // Path state
#define VKDR_DECLARE_PATH_ARRAY(name, Type) VKDR_BUFFER(Type) name;
    VKDR_PATH_ARRAYS(VKDR_DECLARE_PATH_ARRAY)
    VKDR_ADJOINT_PATH_ARRAYS(VKDR_DECLARE_PATH_ARRAY)
#undef VKDR_DECLARE_PATH_ARRAY
    // Queues
    VKDR_BUFFER(QueueCounters) queueCounters;
    VKDR_BUFFER(UintBuffer) queueItems;             // kQueueCount arrays of pathCapacity slots
    VKDR_BUFFER(Vec4Buffer) film;                   // per pixel: rgb sum over samples
    // Differentiation (adjoint pipelines and the loss stage only)
    VKDR_BUFFER(Vec4Buffer) target;                 // per pixel: rgb target image
    VKDR_BUFFER(Vec4Buffer) imageAdjoint;           // per pixel: rgb dLoss/dI, divided by spp; then, with
                                                    // splitSample > 0, the same for samples below it
    VKDR_BUFFER(Int64Buffer) lossSum;               // one fixed-point sum of the per-pixel losses
    VKDR_BUFFER(Vec4Buffer) filmBaseline;           // per pixel: a copy of the film, subtracted by the loss stage on
                                                    // request; with splitSample > 0, the samples below it
#define VKDR_DECLARE_ACCUMULATOR(name, field, floats, copies, items) VKDR_BUFFER(Int64Buffer) name;
    VKDR_GRADIENT_ACCUMULATORS(VKDR_DECLARE_ACCUMULATOR)
#undef VKDR_DECLARE_ACCUMULATOR
    VKDR_BUFFER(UintBuffer) gradientValues;         // the float bits of every accumulator's sums
                                                    // (gradient_values.comp), accumulator after accumulator
    uint pathCapacity;
    uint lightCount;
    uint maxDepth;
    uint seed;
    uint segmentLimit;                              // safety bound on segments per path
    uint lossKind;                                  // kLossL2 or kLossL1
    float filmScale;                                // 1 / spp: film sum to pixel value
    float lossScale;                                // 1 / (3 * pixels): the loss is a mean over pixels and channels
    uint splitSample;                               // > 0: film and loss keep the samples below it apart
    uint imagePixels;                               // width * height
    uint sampleNonScatteringMedia;                  // 1: a gradient pass that wants sigma_s's gradient, which
                                                    // samples collisions in media that do not scatter
    uint defensiveGridCollisions;                   // 1: a gradient pass that wants the density's gradient,
                                                    // whose free flight also collides where the density
                                                    // is 0 (kDefensiveCollisionsPerCrossing)
    uint secondStreamFrom;                          // > 0: samples from this index on draw their points
                                                    // from the next stream (rng.glsl), independent, as the
                                                    // halves of a split gradient estimate must
    uint firstStream;                               // the stream of the samples below secondStreamFrom:
                                                    // kReplayStream for paths independent of any image
    uint sceneMedium;                               // the medium outside every boundary, kNoMediumIndex:
                                                    // vacuum
    // Fixed-point sums from one copy of each gradient accumulator to the next (0: one copy).
#define VKDR_DECLARE_COPY_STRIDE(name, field, floats, copies, items) uint name##CopyStride;
    VKDR_GRADIENT_ACCUMULATORS(VKDR_DECLARE_COPY_STRIDE)
#undef VKDR_DECLARE_COPY_STRIDE
    // Where each accumulator's sums lie in gradientValues, and how many there are in all.
#define VKDR_DECLARE_VALUE_RANGE(name, field, floats, copies, items) uint name##FirstValue; uint name##ValueCount;
    VKDR_GRADIENT_ACCUMULATORS(VKDR_DECLARE_VALUE_RANGE)
#undef VKDR_DECLARE_VALUE_RANGE
    uint gradientValueCount;
};

// Per dispatch values, in push constants next to the RenderParams address.
struct PassConstants {
    uint firstPixel;        // pixels [firstPixel, firstPixel + pixelCount) of this pass
    uint pixelCount;
    uint firstSample;       // samples [firstSample, firstSample + samplesInPass)
    uint samplesInPass;
    uint currentRays;       // kQueueRays0 or kQueueRays1: the queue traced this segment
    uint queueArg;          // queue_prepare: which queue's dispatch to size
    uint clearMask;         // queue_prepare: bit q set -> counts[q] = backCounts[q] = 0
    uint lossImage;         // loss: kLossImageFilm, kLossImageFilmMinusBaseline or kLossImageHalves
};

#ifdef __cplusplus
}  // namespace vkdr::gpu
#endif
#endif
