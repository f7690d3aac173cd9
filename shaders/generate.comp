#version 460
#extension GL_GOOGLE_include_directive : require
// Stage 1: camera rays. One path per (pixel, sample) of the pass; slot s holds pixel
// firstPixel + s % pixelCount and sample firstSample + s / pixelCount.
#include "lib/stage_common.glsl"
#include "lib/path_state.glsl"

void main() {
    uint slot = gl_GlobalInvocationID.x;
    uint pathCount = pass.pixelCount * pass.samplesInPass;
    GpuCamera camera = P.camera;
    // Every camera ray starts in the camera's medium: all at the front, or in vacuum all
    // at the back (queues.glsl).
    bool atBack = camera.medium == kNoMediumIndex;
    if (slot == 0u) {
        P.queueCounters.c.counts[kQueueRays0] = atBack ? 0u : pathCount;
        P.queueCounters.c.backCounts[kQueueRays0] = atBack ? pathCount : 0u;
    }
    if (slot >= pathCount) {
        return;
    }
    PathInfo info = PathInfo(pass.firstPixel + slot % pass.pixelCount,
                             pass.firstSample + slot / pass.pixelCount, 0u, 0u);
    uvec2 pixel = uvec2(info.pixel % camera.width, info.pixel / camera.width);
    // Box filter: a uniform position in the pixel's square; row 0 is the top of the image.
    vec2 jitter = segmentRandom(info, kDimCamera).xy;
    vec2 ndc = (vec2(pixel) + jitter) / vec2(camera.width, camera.height) * 2.0f - 1.0f;
    // Perspective: from the camera through the point at depth 1. Orthographic: from the
    // point on the camera's plane, straight ahead.
    bool orthographic = camera.orthographicHalfHeight > 0.0f;
    float halfHeight = orthographic ? camera.orthographicHalfHeight : camera.tanHalfFovY;
    vec3 onView = vec3(ndc.x * halfHeight * camera.aspect, -ndc.y * halfHeight, 0.0f);
    vec3 local = orthographic ? vec3(0.0f, 0.0f, -1.0f) : normalize(onView - vec3(0.0f, 0.0f, 1.0f));
    vec3 localOrigin = orthographic ? onView : vec3(0.0f);
    vec3 origin = vec3(dot(camera.cameraToWorld[0], vec4(localOrigin, 1.0f)),
                       dot(camera.cameraToWorld[1], vec4(localOrigin, 1.0f)),
                       dot(camera.cameraToWorld[2], vec4(localOrigin, 1.0f)));
    vec3 direction = normalize(vec3(dot(camera.cameraToWorld[0].xyz, local),
                                    dot(camera.cameraToWorld[1].xyz, local),
                                    dot(camera.cameraToWorld[2].xyz, local)));
    storeRay(slot, origin, direction, kNoHit);
    storePathInfo(slot, info);
    P.beta.v[slot] = vec4(1.0f);
    if (kAdjoint) {
        // The radiance buffer keeps the primal replay's L, the replay's starting L_rem.
        P.adjointState.v[slot] = uvec4(0u);
    } else {
        P.radiance.v[slot] = vec4(0.0f);
        P.radianceRounding.v[slot] = vec4(0.0f);
    }
    P.misVertex.v[slot] = vec4(origin, 0.0f);
    P.vertexInfo.v[slot] = uvec4(camera.medium, kVertexSurface, 0u, 0u);
    P.queueItems.v[kQueueRays0 * P.pathCapacity + (atBack ? P.pathCapacity - 1u - slot : slot)] = slot;
}
