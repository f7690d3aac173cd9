// Work queues: a slot array per queue and an atomic counter, two for the shade queue's
// two ends (device_types.h).
#ifndef VKDR_QUEUES_GLSL
#define VKDR_QUEUES_GLSL

// The shade queue keeps its medium vertices at the front of its array and its surface
// vertices at the back, each end walked by a shade pipeline of its own (shade.comp).
// counts[kQueueShade] is its front's size, shadeSurfaces its back's.
uint queueSize(uint queue) {
    return P.queueCounters.c.counts[queue];
}

// The queue's item `index`; for the shade queue, indices past its front count its back
// from the end of the array.
uint queueItem(uint queue, uint index) {
    uint front = P.queueCounters.c.counts[queue];
    uint position = index < front ? index : P.pathCapacity - 1u - (index - front);
    return P.queueItems.v[queue * P.pathCapacity + position];
}

// Appends a path slot, at the back of the array for the shade queue's surface vertices.
// One atomic per subgroup: the lanes that push elect a leader, which reserves room for
// all of them (3-4x faster than one atomic per lane on lavapipe). All the lanes that
// push together must agree on atBack.
void queuePushAt(uint queue, uint slot, bool atBack) {
    uvec4 pushing = subgroupBallot(true);
    uint count = subgroupBallotBitCount(pushing);
    uint rank = subgroupBallotExclusiveBitCount(pushing);
    uint base = 0u;
    if (subgroupElect()) {
        base = atBack ? atomicAdd(P.queueCounters.c.shadeSurfaces, count)
                      : atomicAdd(P.queueCounters.c.counts[queue], count);
    }
    base = subgroupBroadcastFirst(base);
    uint position = atBack ? P.pathCapacity - 1u - (base + rank) : base + rank;
    P.queueItems.v[queue * P.pathCapacity + position] = slot;
}

void queuePush(uint queue, uint slot) {
    queuePushAt(queue, slot, false);
}

// Queues a vertex for shading. The branch keeps the lanes of each kind apart, so each
// pushes with one atomic of its own.
void queueShade(uint slot, bool surface) {
    if (surface) {
        queuePushAt(kQueueShade, slot, true);
    } else {
        queuePushAt(kQueueShade, slot, false);
    }
}

void flagTruncatedLoop() {
    atomicAdd(P.queueCounters.c.truncatedLoops, 1u);
}

#endif
