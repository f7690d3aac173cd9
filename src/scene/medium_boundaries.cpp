#include "scene/medium_boundaries.h"

#include <bit>
#include <map>
#include <unordered_map>

#include "scene/boundary_rays.h"

namespace vkdr {
namespace {

struct Boundary {
    std::string description;  // for messages: the mesh instance and the medium
    uint32_t material = 0;
    std::vector<uint32_t> triangles;
    double volume = 0.0;      // enclosed volume, positive once wound outwards
};

std::vector<Boundary> collectBoundaries(const Scene& scene,
                                        const std::vector<MeshInstance>& instances) {
    std::vector<Boundary> boundaries;
    for (const MeshInstance& instance : instances) {
        std::map<uint32_t, Boundary> byMaterial;
        for (uint32_t t = instance.firstTriangle; t < instance.firstTriangle + instance.triangleCount; ++t) {
            uint32_t material = scene.triangleMaterial[t];
            if (scene.materials[material].isMediumBoundary()) {
                byMaterial[material].triangles.push_back(t);
            }
        }
        for (auto& [material, boundary] : byMaterial) {
            boundary.material = material;
            boundary.description = instance.description + ", boundary of medium '" +
                                   scene.media[size_t(scene.materials[material].interiorMedium)].name + "'";
            boundaries.push_back(std::move(boundary));
        }
    }
    return boundaries;
}

// Vertex ids shared by all corners at the same position: a mesh split at UV seams is
// still closed.
class PositionWelder {
public:
    uint32_t id(glm::vec3 position) {
        position += glm::vec3(0.0f);  // -0 and +0 are the same place
        uint64_t key = std::bit_cast<uint32_t>(position.x);
        key = key * 0x9E3779B97F4A7C15ull ^ std::bit_cast<uint32_t>(position.y);
        key = key * 0x9E3779B97F4A7C15ull ^ std::bit_cast<uint32_t>(position.z);
        auto& bucket = ids_[key];
        for (auto& [stored, storedId] : bucket) {
            if (stored == position) {
                return storedId;
            }
        }
        bucket.emplace_back(position, next_);
        return next_++;
    }

private:
    std::unordered_map<uint64_t, std::vector<std::pair<glm::vec3, uint32_t>>> ids_;
    uint32_t next_ = 0;
};

void requireClosed(const Scene& scene, const Boundary& boundary, const GltfDiagnostics& diagnostics) {
    PositionWelder welder;
    std::unordered_map<uint64_t, uint32_t> directedEdgeUses;
    auto edgeKey = [](uint32_t from, uint32_t to) { return uint64_t(from) << 32 | to; };
    for (uint32_t t : boundary.triangles) {
        glm::uvec3 corners = scene.triangles[t];
        uint32_t ids[3] = {welder.id(scene.positions[corners.x]), welder.id(scene.positions[corners.y]),
                           welder.id(scene.positions[corners.z])};
        if (ids[0] == ids[1] || ids[1] == ids[2] || ids[2] == ids[0]) {
            continue;  // zero area: neither opens nor closes the surface
        }
        for (int e = 0; e < 3; ++e) {
            ++directedEdgeUses[edgeKey(ids[e], ids[(e + 1) % 3])];
        }
    }
    for (auto [edge, uses] : directedEdgeUses) {
        auto reverse = directedEdgeUses.find(edgeKey(uint32_t(edge), uint32_t(edge >> 32)));
        if (reverse == directedEdgeUses.end()) {
            diagnostics.fail(boundary.description,
                             "not a closed mesh: an edge belongs to only one triangle; a medium "
                             "boundary must enclose its volume");
        }
        if (uses != 1 || reverse->second != 1) {
            diagnostics.fail(boundary.description,
                             "not a closed, consistently wound mesh: an edge is shared by more than "
                             "two triangles or by two triangles wound the same way");
        }
    }
}

// Divergence theorem: the sum of signed tetrahedra from the origin to each triangle.
double signedVolume(const Scene& scene, const Boundary& boundary) {
    double volume = 0.0;
    for (uint32_t t : boundary.triangles) {
        glm::uvec3 corners = scene.triangles[t];
        glm::dvec3 p0 = scene.positions[corners.x];
        glm::dvec3 p1 = scene.positions[corners.y];
        glm::dvec3 p2 = scene.positions[corners.z];
        volume += glm::dot(p0, glm::cross(p1, p2)) / 6.0;
    }
    return volume;
}

glm::dvec3 pointOn(const Scene& scene, const Boundary& boundary) {
    glm::uvec3 corners = scene.triangles[boundary.triangles.front()];
    return (glm::dvec3(scene.positions[corners.x]) + glm::dvec3(scene.positions[corners.y]) +
            glm::dvec3(scene.positions[corners.z])) / 3.0;
}

// Cheap intersection test: some of `inner`'s corners (at most 16, spread over it) are
// inside `outer` and some are not.
bool partlyInside(const Scene& scene, const Boundary& inner, const Boundary& outer) {
    size_t step = std::max<size_t>(1, inner.triangles.size() / 16);
    bool anyInside = false;
    bool anyOutside = false;
    for (size_t i = 0; i < inner.triangles.size(); i += step) {
        glm::dvec3 corner = scene.positions[scene.triangles[inner.triangles[i]].x];
        (insideClosedMesh(scene, outer.triangles, corner) ? anyInside : anyOutside) = true;
    }
    return anyInside && anyOutside;
}

void warnAboutOverlaps(const Scene& scene, const std::vector<Boundary>& boundaries,
                       GltfDiagnostics& diagnostics) {
    for (size_t i = 0; i < boundaries.size(); ++i) {
        for (size_t j = i + 1; j < boundaries.size(); ++j) {
            if (partlyInside(scene, boundaries[i], boundaries[j]) ||
                partlyInside(scene, boundaries[j], boundaries[i])) {
                diagnostics.warn(boundaries[i].description,
                                 "intersects " + boundaries[j].description +
                                     "; overlapping media are not supported and render wrongly");
            }
        }
    }
}

}  // namespace

void prepareMediumBoundaries(Scene& scene, const std::vector<MeshInstance>& instances,
                             GltfDiagnostics& diagnostics) {
    scene.triangleOutsideMedium.assign(scene.triangles.size(), kNoMedium);
    std::vector<Boundary> boundaries = collectBoundaries(scene, instances);

    for (Boundary& boundary : boundaries) {
        requireClosed(scene, boundary, diagnostics);
        boundary.volume = signedVolume(scene, boundary);
        if (boundary.volume == 0.0) {
            diagnostics.fail(boundary.description, "encloses no volume");
        }
        if (boundary.volume < 0.0) {
            for (uint32_t t : boundary.triangles) {
                std::swap(scene.triangles[t].y, scene.triangles[t].z);
            }
            boundary.volume = -boundary.volume;
        }
    }

    warnAboutOverlaps(scene, boundaries, diagnostics);

    for (const Boundary& boundary : boundaries) {
        glm::dvec3 point = pointOn(scene, boundary);
        const Boundary* innermost = nullptr;
        for (const Boundary& other : boundaries) {
            if (&other == &boundary) {
                continue;
            }
            if (insideClosedMesh(scene, other.triangles, point) &&
                (!innermost || other.volume < innermost->volume)) {
                innermost = &other;
            }
        }
        int32_t outside = innermost ? scene.materials[innermost->material].interiorMedium
                                    : scene.sceneMedium;
        for (uint32_t t : boundary.triangles) {
            scene.triangleOutsideMedium[t] = outside;
        }
    }
}

}  // namespace vkdr
