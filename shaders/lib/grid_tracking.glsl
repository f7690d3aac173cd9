// Tracking through a density grid medium, whose coefficients are the medium's RGB
// sigma_a and sigma_s times the trilinear density d(x) (docs/density-grids.md). Both
// trackers sample tentative collisions against the majorant cells, walked with a DDA:
// - free flight by delta tracking with the hero channel's rate sigma_t[hero] * m(x),
//   accepting a tentative collision as real with probability d(x) / m(x) (in a gradient
//   pass that differentiates the density, defensively: defensiveChance);
// - transmittance by ratio tracking at the rate max(sigma_t) * m(x).
// Every channel's extinction is a multiple of the same density, so a tentative collision
// is null with the same probability in every channel. The spectral MIS weight of a
// tracked segment therefore depends only on the number of tentative collisions and the
// majorant's integral along the way (heroMisWeight).
#ifndef VKDR_GRID_TRACKING_GLSL
#define VKDR_GRID_TRACKING_GLSL
#include "constants.glsl"
#include "density_grid.glsl"
#include "tracking_random.glsl"

// Below this transmittance ratio tracking plays Russian roulette, ending with probability
// 3/4 and else carrying on four times stronger (as pbrt-v4 does), which bounds its
// expected work in dense media.
const float kRatioTrackingRouletteBelow = 0.05f;
const float kRatioTrackingRouletteSurvival = 0.25f;

// A ray in a grid's index coordinates, index(t) = origin + t direction, where t is the
// world-space distance along the world ray.
struct GridRay {
    vec3 origin;
    vec3 direction;
};

GridRay gridRay(GpuDensityGrid grid, vec3 origin, vec3 direction) {
    GridRay ray;
    for (int k = 0; k < 3; ++k) {
        ray.origin[k] = dot(vec3(grid.worldToIndex[k]), origin) + grid.worldToIndex[k].w;
        ray.direction[k] = dot(vec3(grid.worldToIndex[k]), direction);
    }
    return ray;
}

// The eight voxels a trilinear lookup at index coordinates p blends: corner c (bit 0: x,
// bit 1: y, bit 2: z) is voxel floor(p) + trilinearCorner(c), weighted by
// trilinearWeight(p - floor(p), that corner). The adjoint spreads a density's gradient
// over the same voxels with the same weights.
ivec3 trilinearCorner(int corner) {
    return ivec3(corner & 1, (corner >> 1) & 1, corner >> 2);
}

float trilinearWeight(vec3 fraction, ivec3 corner) {
    vec3 w = mix(vec3(1.0f) - fraction, fraction, vec3(corner));
    return w.x * w.y * w.z;
}

float gridDensity(GpuDensityGrid grid, vec3 index) {
    vec3 base = floor(index);
    float density = 0.0f;
    for (int corner = 0; corner < 8; ++corner) {
        ivec3 offset = trilinearCorner(corner);
        density += trilinearWeight(index - base, offset) * gridVoxel(grid, ivec3(base) + offset);
    }
    return density;
}

// The trilinear RGB of an albedo grid, with gridDensity's weights.
vec3 gridAlbedo(GpuDensityGrid grid, vec3 index) {
    vec3 base = floor(index);
    vec3 albedo = vec3(0.0f);
    for (int corner = 0; corner < 8; ++corner) {
        ivec3 offset = trilinearCorner(corner);
        albedo += trilinearWeight(index - base, offset) * gridVoxelRgb(grid, ivec3(base) + offset);
    }
    return albedo;
}

// A DDA walk over the majorant cells along a ray: the current cell and where the ray
// leaves it through each axis's next face.
struct MajorantWalk {
    ivec3 cell;
    ivec3 step;
    vec3 tNext;   // distance at which the ray crosses the next face along each axis
    vec3 tDelta;  // distance between faces along each axis
    float t;      // where the walk is
    float tEnd;   // where the ray leaves the cells, or its own end
};

// The part of [0, tMax) where the ray is inside the majorant cells, which hold all of the
// density; empty (x >= y) when it misses them.
vec2 cellsInterval(GpuDensityGrid grid, GridRay ray, float tMax) {
    vec3 lower = vec3(ivec3(grid.majorantOrigin));
    vec3 upper = lower + vec3(ivec3(grid.majorantCells) * kMajorantCellVoxels);
    float enter = 0.0f;
    float exit = tMax;
    for (int k = 0; k < 3; ++k) {
        if (ray.direction[k] == 0.0f) {
            if (ray.origin[k] < lower[k] || ray.origin[k] >= upper[k]) {
                exit = -1.0f;
            }
            continue;
        }
        float t0 = (lower[k] - ray.origin[k]) / ray.direction[k];
        float t1 = (upper[k] - ray.origin[k]) / ray.direction[k];
        enter = max(enter, min(t0, t1));
        exit = min(exit, max(t0, t1));
    }
    return vec2(enter, exit);
}

// Starts a walk along [0, tMax); done at once when the ray misses the cells.
MajorantWalk startMajorantWalk(GpuDensityGrid grid, GridRay ray, float tMax) {
    MajorantWalk walk;
    vec3 cellOrigin = (ray.origin - vec3(ivec3(grid.majorantOrigin))) / float(kMajorantCellVoxels);
    vec3 cellDirection = ray.direction / float(kMajorantCellVoxels);
    vec2 interval = cellsInterval(grid, ray, tMax);
    float enter = interval.x;
    float exit = interval.y;
    walk.t = enter;
    walk.tEnd = exit;
    if (!(enter < exit)) {
        walk.tEnd = walk.t;
        return walk;
    }
    vec3 start = cellOrigin + enter * cellDirection;
    walk.cell = clamp(ivec3(floor(start)), ivec3(0), ivec3(grid.majorantCells) - 1);
    for (int k = 0; k < 3; ++k) {
        if (cellDirection[k] > 0.0f) {
            walk.step[k] = 1;
            walk.tDelta[k] = 1.0f / cellDirection[k];
            walk.tNext[k] = enter + (float(walk.cell[k] + 1) - start[k]) / cellDirection[k];
        } else if (cellDirection[k] < 0.0f) {
            walk.step[k] = -1;
            walk.tDelta[k] = -1.0f / cellDirection[k];
            walk.tNext[k] = enter + (float(walk.cell[k]) - start[k]) / cellDirection[k];
        } else {
            walk.step[k] = 0;
            walk.tDelta[k] = kFar;
            walk.tNext[k] = kFar;
        }
    }
    return walk;
}

bool walkDone(MajorantWalk walk) {
    return !(walk.t < walk.tEnd);
}

// Where the walk leaves its current cell.
float cellExit(MajorantWalk walk) {
    return min(min(min(walk.tNext.x, walk.tNext.y), walk.tNext.z), walk.tEnd);
}

void advanceToNextCell(INOUT(MajorantWalk) walk, GpuDensityGrid grid) {
    float exit = cellExit(walk);
    int axis = walk.tNext.x <= walk.tNext.y ? (walk.tNext.x <= walk.tNext.z ? 0 : 2)
                                            : (walk.tNext.y <= walk.tNext.z ? 1 : 2);
    walk.t = exit;
    walk.cell[axis] += walk.step[axis];
    walk.tNext[axis] += walk.tDelta[axis];
    if (walk.cell[axis] < 0 || walk.cell[axis] >= grid.majorantCells[axis]) {
        walk.tEnd = walk.t;
    }
}

// The majorant density's integral over [0, tMax) of the ray: sigma_t times it is the
// majorant's optical depth, and ratio tracking samples max(sigma_t) times it tentative
// collisions on average.
float majorantIntegral(GpuDensityGrid grid, GridRay ray, float tMax) {
    MajorantWalk walk = startMajorantWalk(grid, ray, tMax);
    float integral = 0.0f;
    while (!walkDone(walk)) {
        integral += gridMajorant(grid, walk.cell) * (cellExit(walk) - walk.t);
        advanceToNextCell(walk, grid);
    }
    return integral;
}

// The outcome of delta tracking along [0, tMax).
struct GridFreeFlight {
    float t;                // the real collision, the pause, or tMax
    bool collided;          // a real collision at t
    vec3 index;             // the grid's index coordinates of the collision
    float density;          // the density there
    float chance;           // the density a real collision was accepted against there (defensiveChance)
    bool paused;            // the step bound was reached at t, short of a decision
    uint tentative;         // tentative collisions sampled, the real one included
    float majorantIntegral; // integral of the majorant density over [0, t]
    float nullWeight;       // the null collisions' weights (1 unless defensive), the same in every channel
};

// The density against which a tentative collision at `density` under `majorant` is
// accepted as real. Where the density is 0 a gradient pass that differentiates it
// accepts some (device_types.h): as if the density were `defensiveDensity`, at most
// kDefensiveCollisionShare of the majorant. Such a real collision weighs 0 (the primal
// path ends, while the adjoint follows its derivative), a null one
// majorant / (majorant - chance); both are the same in every channel, so the spectral
// MIS weight is unchanged. Elsewhere, and in other passes, the chance is the density.
float defensiveChance(float density, float majorant, float defensiveDensity) {
    return density > 0.0f ? density : min(defensiveDensity, kDefensiveCollisionShare * majorant);
}

// Whether a lookup at index coordinates p blends any voxel of the grid's box: elsewhere
// (in the majorant cells' rounding beyond it) no voxel is a parameter, and a defensive
// collision would only end the path.
bool blendsVoxelsOfTheBox(GpuDensityGrid grid, vec3 p) {
    vec3 first = vec3(ivec3(grid.firstVoxel));
    return all(greaterThanEqual(p, first - 1.0f)) && all(lessThan(p, first + vec3(ivec3(grid.size))));
}

// Delta tracking in the hero channel, whose extinction per unit density is `rate`.
// `first` supplies the first distance (x) and acceptance (y) numbers; later ones come
// from `random`. A `defensiveDensity` above 0 gives an empty cell the majorant
// defensiveDensity / kDefensiveCollisionShare and accepts collisions by defensiveChance.
GridFreeFlight trackFreeFlight(GpuDensityGrid grid, vec3 origin, vec3 direction, float tMax, float rate, vec2 first,
                               float defensiveDensity, INOUT(TrackingRandom) random) {
    GridFreeFlight flight;
    flight.t = tMax;
    flight.collided = false;
    flight.index = vec3(0.0f);
    flight.density = 0.0f;
    flight.chance = 0.0f;
    flight.paused = false;
    flight.tentative = 0u;
    flight.majorantIntegral = 0.0f;
    flight.nullWeight = 1.0f;
    float emptyCellMajorant = defensiveDensity / kDefensiveCollisionShare;
    GridRay ray = gridRay(grid, origin, direction);
    MajorantWalk walk = startMajorantWalk(grid, ray, tMax);
    float tau = -log(1.0f - first.x);  // optical depth to the next tentative collision
    float accept = first.y;
    for (uint steps = 0u; !walkDone(walk); ++steps) {
        if (steps == kMaxFreeFlightSteps) {
            flight.t = walk.t;
            flight.paused = true;
            return flight;
        }
        float exit = cellExit(walk);
        float majorant = gridMajorant(grid, walk.cell);
        majorant = majorant > 0.0f ? majorant : emptyCellMajorant;
        float cellDepth = majorant * rate * (exit - walk.t);
        if (tau < cellDepth) {
            float dt = tau / (majorant * rate);
            flight.majorantIntegral += majorant * dt;
            walk.t += dt;
            ++flight.tentative;
            vec3 point = ray.origin + walk.t * ray.direction;
            float density = gridDensity(grid, point);
            float chance =
                defensiveChance(density, majorant, blendsVoxelsOfTheBox(grid, point) ? defensiveDensity : 0.0f);
            if (accept * majorant < chance) {
                flight.t = walk.t;
                flight.collided = true;
                flight.index = point;
                flight.density = density;
                flight.chance = chance;
                return flight;
            }
            if (chance != density) {
                flight.nullWeight *= (majorant - density) / (majorant - chance);
            }
            vec4 u = nextTrackingRandom(random);
            tau = -log(1.0f - u.x);
            accept = u.y;
            continue;
        }
        tau -= cellDepth;
        flight.majorantIntegral += majorant * (exit - walk.t);
        advanceToNextCell(walk, grid);
    }
    return flight;
}

// The one-sample MIS weight p_c / average_k p_k of each channel c over the choice of hero
// channel, for a tracked segment with `tentative` tentative collisions and majorant
// integral `integral`: sampled with hero k, its density is sigma_t[k]^tentative
// exp(-sigma_t[k] integral) times factors common to all channels. A channel without
// extinction has density 0 once there is a tentative collision, 1 before.
vec3 heroMisWeight(vec3 sigma_t, uint tentative, float integral) {
    vec3 logDensity;
    bvec3 possible;
    float largest = -kFar;
    for (int c = 0; c < 3; ++c) {
        possible[c] = sigma_t[c] > 0.0f || tentative == 0u;
        logDensity[c] = sigma_t[c] > 0.0f ? float(tentative) * log(sigma_t[c]) - sigma_t[c] * integral : 0.0f;
        if (possible[c]) {
            largest = max(largest, logDensity[c]);
        }
    }
    vec3 density;
    for (int c = 0; c < 3; ++c) {
        density[c] = possible[c] ? exp(logDensity[c] - largest) : 0.0f;
    }
    return density / average(density);
}

// Distances along a ray, in ascending order, at which ratioTrackTransmittanceAt also
// reports its running estimate of the transmittance from 0.
const uint kMaxTransmittancePoints = 4u;

struct TransmittancePoints {
    float t[kMaxTransmittancePoints];
    vec3 transmittance[kMaxTransmittancePoints];
    uint count;
};

// Gives the points before distance t (from `next` on) the running estimate.
void recordTransmittanceBefore(INOUT(TransmittancePoints) points, INOUT(uint) next, float t, vec3 transmittance) {
    for (; next < points.count && points.t[next] < t; ++next) {
        points.transmittance[next] = transmittance;
    }
}

void recordRemainingTransmittance(INOUT(TransmittancePoints) points, uint next, vec3 transmittance) {
    for (; next < points.count; ++next) {
        points.transmittance[next] = transmittance;
    }
}

// Ratio tracking along [0, tMax): an unbiased estimate of each channel's transmittance
// exp(-sigma_t integral of d). The product of the ratios of the tentative collisions
// before any distance t is an unbiased estimate of the transmittance up to t (the
// tentative collisions before t are a Poisson process of their own), which `points`
// receives at its distances. Each tentative collision and majorant cell takes one of
// `stepsLeft`, which a caller shares among the segments of one ray; `truncated` is set,
// and 0 returned (and reported), where they run out.
vec3 ratioTrackTransmittanceAt(GpuDensityGrid grid, vec3 origin, vec3 direction, float tMax, vec3 sigma_t,
                               INOUT(TrackingRandom) random, INOUT(uint) stepsLeft, INOUT(bool) truncated,
                               INOUT(TransmittancePoints) points) {
    vec3 transmittance = vec3(1.0f);
    uint next = 0u;
    float rate = maxComponent(sigma_t);
    if (rate <= 0.0f) {
        recordRemainingTransmittance(points, next, transmittance);
        return transmittance;
    }
    GridRay ray = gridRay(grid, origin, direction);
    MajorantWalk walk = startMajorantWalk(grid, ray, tMax);
    float tau = -log(1.0f - nextTrackingRandom(random).x);
    while (!walkDone(walk)) {
        if (stepsLeft == 0u) {
            truncated = true;
            transmittance = vec3(0.0f);
            break;
        }
        --stepsLeft;
        float exit = cellExit(walk);
        float majorant = gridMajorant(grid, walk.cell);
        float cellDepth = majorant * rate * (exit - walk.t);
        if (tau < cellDepth) {
            float rateHere = majorant * rate;
            walk.t += tau / rateHere;
            recordTransmittanceBefore(points, next, walk.t, transmittance);
            float density = gridDensity(grid, ray.origin + walk.t * ray.direction);
            transmittance *= max(vec3(0.0f), vec3(1.0f) - sigma_t * (density / rateHere));
            vec4 u = nextTrackingRandom(random);
            float largest = maxComponent(transmittance);
            if (largest < kRatioTrackingRouletteBelow) {
                if (largest <= 0.0f || u.y >= kRatioTrackingRouletteSurvival) {
                    transmittance = vec3(0.0f);
                    break;
                }
                transmittance /= kRatioTrackingRouletteSurvival;
            }
            tau = -log(1.0f - u.x);
            continue;
        }
        tau -= cellDepth;
        advanceToNextCell(walk, grid);
    }
    recordRemainingTransmittance(points, next, transmittance);
    return transmittance;
}

// Ratio tracking's estimate of the transmittance over [0, tMax) alone.
vec3 ratioTrackTransmittance(GpuDensityGrid grid, vec3 origin, vec3 direction, float tMax, vec3 sigma_t,
                             INOUT(TrackingRandom) random, INOUT(uint) stepsLeft, INOUT(bool) truncated) {
    TransmittancePoints none;
    none.count = 0u;
    return ratioTrackTransmittanceAt(grid, origin, direction, tMax, sigma_t, random, stepsLeft, truncated, none);
}

// Stratified points along the ray's part in the grid, with which the adjoint estimates
// integrals of the density (and of its derivatives) over [0, tMax), independently of the
// tracking that chose the path.
const uint kDensityIntegralPoints = 4u;

// The grid's index coordinates of point `k` of kDensityIntegralPoints along `interval`
// of the ray (cellsInterval), offset by `u` within its stratum.
vec3 densityIntegralPoint(GridRay ray, vec2 interval, uint k, float u) {
    float t = interval.x + (float(k) + u) * ((interval.y - interval.x) / float(kDensityIntegralPoints));
    return ray.origin + t * ray.direction;
}

#endif
