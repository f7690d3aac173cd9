// Work queues: a slot array per queue and an atomic counter, two for the shade queue's
// two ends (device_types.h).
#ifndef VKDR_QUEUES_GLSL
#define VKDR_QUEUES_GLSL

// A queue's array holds items at both ends: counts[queue] of them from the front and
// backCounts[queue] from the back (device_types.h: which kind of item goes where).
// Stages whose work differs by kind have a pipeline for each end (kQueueEnd), so that
// neither kind runs the other's code.
uint queueSize(uint queue) {
    return P.queueCounters.c.counts[queue] + P.queueCounters.c.backCounts[queue];
}

// The queue's item `index`: its front's items first, then its back's from the end of
// the array.
uint queueItem(uint queue, uint index) {
    uint front = P.queueCounters.c.counts[queue];
    uint position = index < front ? index : P.pathCapacity - 1u - (index - front);
    return P.queueItems.v[queue * P.pathCapacity + position];
}

// The size of the end of the queue that this pipeline walks (kQueueEnd), and its item
// `index`.
uint endSize(uint queue) {
    return kQueueEnd == kFrontEnd ? P.queueCounters.c.counts[queue] : P.queueCounters.c.backCounts[queue];
}

uint endItem(uint queue, uint index) {
    return queueItem(queue, kQueueEnd == kFrontEnd ? index : P.queueCounters.c.counts[queue] + index);
}

// Appends a path slot at the front of the queue's array or at its back.
// One atomic per subgroup and end: the lanes that push to one end elect a leader, which
// reserves room for all of them (3-4x faster than one atomic per lane on lavapipe). The
// branch keeps the lanes of the two ends apart.
void reserveAndPush(uint queue, uint slot, bool atBack) {
    uvec4 pushing = subgroupBallot(true);
    uint count = subgroupBallotBitCount(pushing);
    uint rank = subgroupBallotExclusiveBitCount(pushing);
    uint base = 0u;
    if (subgroupElect()) {
        base = atBack ? atomicAdd(P.queueCounters.c.backCounts[queue], count)
                      : atomicAdd(P.queueCounters.c.counts[queue], count);
    }
    base = subgroupBroadcastFirst(base);
    uint position = atBack ? P.pathCapacity - 1u - (base + rank) : base + rank;
    P.queueItems.v[queue * P.pathCapacity + position] = slot;
}

void queuePushAt(uint queue, uint slot, bool atBack) {
    if (atBack) {
        reserveAndPush(queue, slot, true);
    } else {
        reserveAndPush(queue, slot, false);
    }
}

void queuePush(uint queue, uint slot) {
    queuePushAt(queue, slot, false);
}

// Queues a vertex for shading: surface vertices at the back, medium vertices at the front.
void queueShade(uint slot, bool surface) {
    queuePushAt(kQueueShade, slot, surface);
}

// Queues a ray in `medium` (kNoMediumIndex: vacuum) to be traced: in vacuum at the back.
void queueRay(uint queue, uint slot, uint medium) {
    queuePushAt(queue, slot, medium == kNoMediumIndex);
}

void flagTruncatedLoop() {
    atomicAdd(P.queueCounters.c.truncatedLoops, 1u);
}

#endif
