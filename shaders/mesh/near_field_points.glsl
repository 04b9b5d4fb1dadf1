// The near field's points (src/mesh/near_field_cache.h): triangle t has a grid of R(t) + 1 points
// per edge, point (i, j) at barycentric (1 - (i + j) / R, i / R, j / R) of corners (a, b, c), stored
// row by row (j) from the triangle's first. Each triangle's entry is first << 3 | (R - 1).
// near_field_cache.comp evaluates the points once per light change, near_field_radiosity.comp adds
// the vertices' radiosity to them; the combine interpolates the three around a pixel.
int nearFieldFirstPoint(uint entry) { return int(entry >> 3u); }
int nearFieldDivisions(uint entry) { return int(entry & 7u) + 1; }

// Point (i, j) of a grid with r divisions, counted from the triangle's first.
int nearFieldPointIndex(int i, int j, int r) { return j * (r + 1) - (j * (j - 1)) / 2 + i; }

// Point k of a grid with r divisions, counted from the triangle's first: its (i, j).
ivec2 nearFieldPointCell(int k, int r) {
    int j = 0;
    while (k > r - j) {  // row j holds r + 1 - j points
        k -= r + 1 - j;
        ++j;
    }
    return ivec2(k, j);
}

// The barycentric weights of corners (a, b, c) at point k of a grid with r divisions.
vec3 nearFieldPointWeights(int k, int r) {
    ivec2 ij = nearFieldPointCell(k, r);
    return vec3(float(r - ij.x - ij.y), float(ij.x), float(ij.y)) / float(r);
}
