// The multiple-scattering cache's photon sums: kSlotsPerCell slots per cell, each a 64-bit
// two's-complement fixed-point sum in two uints (low word, high word), cell after cell. Where one
// storage buffer would exceed GL_MAX_SHADER_STORAGE_BLOCK_SIZE they are split into SUMS_PARTS
// bindings of sumsCellsPerPart cells each (FluenceCache::bindSums). Define SUMS_WRITABLE before
// including to add to them.
#ifndef SUMS_PARTS
#define SUMS_PARTS 1
#endif
#ifdef SUMS_WRITABLE
#define SUMS_ACCESS
#else
#define SUMS_ACCESS readonly
#endif
layout(std430, binding = 2) SUMS_ACCESS buffer Sums0 { uint sums0[]; };
#if SUMS_PARTS > 1
layout(std430, binding = 5) SUMS_ACCESS buffer Sums1 { uint sums1[]; };
#endif
#if SUMS_PARTS > 2
layout(std430, binding = 6) SUMS_ACCESS buffer Sums2 { uint sums2[]; };
#endif
#if SUMS_PARTS > 3
layout(std430, binding = 7) SUMS_ACCESS buffer Sums3 { uint sums3[]; };
#endif
uniform uint sumsCellsPerPart;

const uint kSlotsPerCell = 23u;

// Where a cell's first slot is: its part, and the slot's index within that part.
struct SumsSlot {
    uint part;
    uint slot;
};

SumsSlot sumsOfCell(uint cell) {
    uint part = SUMS_PARTS > 1 ? cell / sumsCellsPerPart : 0u;
    return SumsSlot(part, (cell - part * sumsCellsPerPart) * kSlotsPerCell);
}

SumsSlot nextSlot(SumsSlot s, uint k) { return SumsSlot(s.part, s.slot + k); }

// Word `word` (0: low, 1: high) of slot s.
uint sumsWord(SumsSlot s, uint word) {
    uint i = 2u * s.slot + word;
#if SUMS_PARTS > 1
    if (s.part == 1u) return sums1[i];
#endif
#if SUMS_PARTS > 2
    if (s.part == 2u) return sums2[i];
#endif
#if SUMS_PARTS > 3
    if (s.part == 3u) return sums3[i];
#endif
    return sums0[i];
}

#ifdef SUMS_WRITABLE
// Adds v to word `word` of slot s atomically; returns the word before.
uint sumsAdd(SumsSlot s, uint word, uint v) {
    uint i = 2u * s.slot + word;
#if SUMS_PARTS > 1
    if (s.part == 1u) return atomicAdd(sums1[i], v);
#endif
#if SUMS_PARTS > 2
    if (s.part == 2u) return atomicAdd(sums2[i], v);
#endif
#if SUMS_PARTS > 3
    if (s.part == 3u) return atomicAdd(sums3[i], v);
#endif
    return atomicAdd(sums0[i], v);
}
#endif
