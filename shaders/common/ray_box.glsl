// Reciprocal of a ray direction for slab tests, with zero components replaced by a tiny value
// of the same sign, so the tests compute with large finite numbers. With exact infinities a
// compiler that reassociates (NVIDIA's does) can turn (hi - o) * inv into hi * inv - o * inv =
// inf - inf = NaN, and an axis-aligned ray then misses the box (volumes cast no shadow on the
// floor straight below them).
vec3 safeInverse(vec3 d) {
    const float tiny = 1e-20;
    return vec3(1.0) / vec3(abs(d.x) < tiny ? (d.x < 0.0 ? -tiny : tiny) : d.x,
                            abs(d.y) < tiny ? (d.y < 0.0 ? -tiny : tiny) : d.y,
                            abs(d.z) < tiny ? (d.z < 0.0 ? -tiny : tiny) : d.z);
}
