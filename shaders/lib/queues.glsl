// Work queues: an atomic counter plus a slot array per queue (device_types.h).
#ifndef VKDR_QUEUES_GLSL
#define VKDR_QUEUES_GLSL

uint queueSize(uint queue) {
    return P.queueCounters.c.counts[queue];
}

uint queueItem(uint queue, uint index) {
    return P.queueItems.v[queue * P.pathCapacity + index];
}

// Appends a path slot. One atomic per subgroup: the lanes that push elect a leader,
// which reserves room for all of them (3-4x faster than one atomic per lane on lavapipe).
void queuePush(uint queue, uint slot) {
    uvec4 pushing = subgroupBallot(true);
    uint count = subgroupBallotBitCount(pushing);
    uint rank = subgroupBallotExclusiveBitCount(pushing);
    uint base = 0u;
    if (subgroupElect()) {
        base = atomicAdd(P.queueCounters.c.counts[queue], count);
    }
    base = subgroupBroadcastFirst(base);
    P.queueItems.v[queue * P.pathCapacity + base + rank] = slot;
}

void flagTruncatedLoop() {
    atomicAdd(P.queueCounters.c.truncatedLoops, 1u);
}

#endif
