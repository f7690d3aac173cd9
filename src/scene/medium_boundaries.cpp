#include "scene/medium_boundaries.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <span>
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

// Each triangle's corners as welded vertex ids.
using Corners = std::array<uint32_t, 3>;

std::vector<Corners> weldedCorners(const Scene& scene, const Boundary& boundary) {
    PositionWelder welder;
    std::vector<Corners> corners;
    corners.reserve(boundary.triangles.size());
    for (uint32_t t : boundary.triangles) {
        const glm::uvec3 triangle = scene.triangles[t];
        corners.push_back({welder.id(scene.positions[triangle.x]), welder.id(scene.positions[triangle.y]),
                           welder.id(scene.positions[triangle.z])});
    }
    return corners;
}

// Zero area: neither opens nor closes the surface, and its winding does not matter.
bool isDegenerate(const Corners& ids) { return ids[0] == ids[1] || ids[1] == ids[2] || ids[2] == ids[0]; }

void requireClosed(const Boundary& boundary, const std::vector<Corners>& corners,
                   const GltfDiagnostics& diagnostics) {
    std::unordered_map<uint64_t, uint32_t> directedEdgeUses;
    auto edgeKey = [](uint32_t from, uint32_t to) { return uint64_t(from) << 32 | to; };
    for (const Corners& ids : corners) {
        if (isDegenerate(ids)) continue;
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
double signedVolume(const Scene& scene, std::span<const uint32_t> triangles) {
    double volume = 0.0;
    for (uint32_t t : triangles) {
        glm::uvec3 corners = scene.triangles[t];
        glm::dvec3 p0 = scene.positions[corners.x];
        glm::dvec3 p1 = scene.positions[corners.y];
        glm::dvec3 p2 = scene.positions[corners.z];
        volume += glm::dot(p0, glm::cross(p1, p2)) / 6.0;
    }
    return volume;
}

// One connected closed surface of a boundary.
struct Shell {
    std::vector<uint32_t> triangles;
    double volume = 0.0;  // signed: positive where wound outwards
    glm::dvec3 lower{std::numeric_limits<double>::infinity()};  // bounding box
    glm::dvec3 upper{-std::numeric_limits<double>::infinity()};
};

// The representative of `i`'s set in a union-find forest, halving paths on the way.
uint32_t rootOf(std::vector<uint32_t>& parent, uint32_t i) {
    while (parent[i] != i) {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    return i;
}

// The boundary's shells: its triangles joined by shared edges, zero-area ones left out.
std::vector<Shell> shellsOf(const Scene& scene, const Boundary& boundary, const std::vector<Corners>& corners) {
    std::vector<uint32_t> parent(corners.size());
    std::iota(parent.begin(), parent.end(), 0u);
    std::unordered_map<uint64_t, uint32_t> edgeTriangle;  // undirected edge -> a triangle on it
    for (uint32_t i = 0; i < corners.size(); ++i) {
        if (isDegenerate(corners[i])) continue;
        for (int e = 0; e < 3; ++e) {
            const auto [a, b] = std::minmax(corners[i][e], corners[i][(e + 1) % 3]);
            auto [found, added] = edgeTriangle.try_emplace(uint64_t(a) << 32 | b, i);
            if (!added) parent[rootOf(parent, i)] = rootOf(parent, found->second);
        }
    }
    std::unordered_map<uint32_t, size_t> shellOfRoot;
    std::vector<Shell> shells;
    for (uint32_t i = 0; i < corners.size(); ++i) {
        if (isDegenerate(corners[i])) continue;
        auto [found, added] = shellOfRoot.try_emplace(rootOf(parent, i), shells.size());
        if (added) shells.emplace_back();
        Shell& shell = shells[found->second];
        const uint32_t t = boundary.triangles[i];
        shell.triangles.push_back(t);
        for (int c = 0; c < 3; ++c) {
            shell.lower = glm::min(shell.lower, glm::dvec3(scene.positions[scene.triangles[t][c]]));
            shell.upper = glm::max(shell.upper, glm::dvec3(scene.positions[scene.triangles[t][c]]));
        }
    }
    for (Shell& shell : shells) shell.volume = signedVolume(scene, shell.triangles);
    return shells;
}

// Whether `point` lies inside `shell`, however the shell is wound.
bool insideShell(const Scene& scene, const Shell& shell, glm::dvec3 point) {
    if (glm::any(glm::lessThan(point, shell.lower)) || glm::any(glm::greaterThan(point, shell.upper))) return false;
    std::optional<BoundaryHit> hit = closestBoundaryHit(scene, shell.triangles, point, kContainmentRayDirection);
    return hit && hit->leaving == (shell.volume > 0.0);
}

glm::dvec3 centreOf(const Scene& scene, uint32_t triangle) {
    glm::uvec3 corners = scene.triangles[triangle];
    return (glm::dvec3(scene.positions[corners.x]) + glm::dvec3(scene.positions[corners.y]) +
            glm::dvec3(scene.positions[corners.z])) / 3.0;
}

// Whether `shell` lies inside `other`: its box within the other's (a shell nested in
// another must be), and the centre of its first triangle inside.
bool nestedIn(const Scene& scene, const Shell& shell, const Shell& other) {
    const bool boxWithin = glm::all(glm::greaterThanEqual(shell.lower, other.lower)) &&
                           glm::all(glm::lessThanEqual(shell.upper, other.upper));
    return boxWithin && insideShell(scene, other, centreOf(scene, shell.triangles.front()));
}

// Whether of `shell`'s triangle centres (at most 16, spread over it) some lie inside
// `other` and some outside.
bool straddles(const Scene& scene, const Shell& shell, const Shell& other) {
    const size_t step = std::max<size_t>(1, shell.triangles.size() / 16);
    bool anyInside = false, anyOutside = false;
    for (size_t i = 0; i < shell.triangles.size() && !(anyInside && anyOutside); i += step) {
        (insideShell(scene, other, centreOf(scene, shell.triangles[i])) ? anyInside : anyOutside) = true;
    }
    return anyInside && anyOutside;
}

// Whether the surfaces of two shells cross, so that neither nests in the other.
bool intersect(const Scene& scene, const Shell& a, const Shell& b) {
    const bool boxesMeet = glm::all(glm::lessThanEqual(a.lower, b.upper)) &&
                           glm::all(glm::lessThanEqual(b.lower, a.upper));
    return boxesMeet && (straddles(scene, a, b) || straddles(scene, b, a));
}

// Whether `shell` should be wound outwards: unless it lies inside an odd number of the
// boundary's other shells, so that it bounds a cavity in the medium. A shell wound as
// the shell directly around it is refused: a cavity wound the wrong way, or a medium
// inside itself, is a guess either way. Shells that intersect (`crossing`; spheres of a
// cloud joined into one mesh) do not nest.
bool windsOutwards(const Scene& scene, const Boundary& boundary, const std::vector<Shell>& shells, size_t s,
                   const std::vector<std::vector<size_t>>& crossing, const GltfDiagnostics& diagnostics) {
    const Shell& shell = shells[s];
    const Shell* around = nullptr;  // the smallest shell containing this one
    size_t containing = 0;
    for (size_t o = 0; o < shells.size(); ++o) {
        const Shell& other = shells[o];
        const bool crosses = std::find(crossing[s].begin(), crossing[s].end(), o) != crossing[s].end();
        if (o == s || crosses || !nestedIn(scene, shell, other)) continue;
        ++containing;
        if (!around || std::abs(other.volume) < std::abs(around->volume)) around = &other;
    }
    if (around && (around->volume > 0.0) == (shell.volume > 0.0)) {
        diagnostics.fail(boundary.description,
                         "a closed surface of it lies inside another and is wound the same way; wind a cavity "
                         "opposite to the surface around it, or give a nested medium a material of its own");
    }
    return containing % 2 == 0;
}

// The shells each shell intersects; warns once if any do, as overlapping boundaries are.
std::vector<std::vector<size_t>> crossingShells(const Scene& scene, const Boundary& boundary,
                                                const std::vector<Shell>& shells, GltfDiagnostics& diagnostics) {
    std::vector<std::vector<size_t>> crossing(shells.size());
    bool any = false;
    for (size_t a = 0; a < shells.size(); ++a) {
        for (size_t b = a + 1; b < shells.size(); ++b) {
            if (intersect(scene, shells[a], shells[b])) {
                crossing[a].push_back(b);
                crossing[b].push_back(a);
                any = true;
            }
        }
    }
    if (any) {
        diagnostics.warn(boundary.description, "two closed surfaces of it intersect; overlapping media are not "
                                               "supported and render wrongly");
    }
    return crossing;
}

// Winds every shell of `boundary` so that its normals point out of the medium; sets the
// boundary's volume, the medium's net volume.
void orientShells(Scene& scene, Boundary& boundary, const std::vector<Corners>& corners,
                  GltfDiagnostics& diagnostics) {
    const std::vector<Shell> shells = shellsOf(scene, boundary, corners);
    for (const Shell& shell : shells) {
        if (shell.volume == 0.0) diagnostics.fail(boundary.description, "encloses no volume");
    }
    const std::vector<std::vector<size_t>> crossing = crossingShells(scene, boundary, shells, diagnostics);
    std::vector<bool> outwards;
    for (size_t s = 0; s < shells.size(); ++s) {
        outwards.push_back(windsOutwards(scene, boundary, shells, s, crossing, diagnostics));
    }
    boundary.volume = 0.0;
    for (size_t s = 0; s < shells.size(); ++s) {
        if ((shells[s].volume > 0.0) != outwards[s]) {
            for (uint32_t t : shells[s].triangles) std::swap(scene.triangles[t].y, scene.triangles[t].z);
        }
        boundary.volume += outwards[s] ? std::abs(shells[s].volume) : -std::abs(shells[s].volume);
    }
    if (!(boundary.volume > 0.0)) diagnostics.fail(boundary.description, "encloses no volume");
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
        const std::vector<Corners> corners = weldedCorners(scene, boundary);
        requireClosed(boundary, corners, diagnostics);
        orientShells(scene, boundary, corners, diagnostics);
    }

    warnAboutOverlaps(scene, boundaries, diagnostics);

    for (const Boundary& boundary : boundaries) {
        glm::dvec3 point = centreOf(scene, boundary.triangles.front());
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
