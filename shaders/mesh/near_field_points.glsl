// The near field's points (src/mesh/near_field_cache.h): triangle t has a grid of R(t) + 1 points
// per edge, point (i, j) at barycentric (1 - (i + j) / R, i / R, j / R) of corners (a, b, c), stored
// row by row (j) from the triangle's first. Each triangle's entry is first << 3 | (R - 1).
// near_field_cache.comp evaluates the points once per light change; the combine interpolates the
// three around a pixel.
int nearFieldFirstPoint(uint entry) { return int(entry >> 3u); }
int nearFieldDivisions(uint entry) { return int(entry & 7u) + 1; }

// Point (i, j) of a grid with r divisions, counted from the triangle's first.
int nearFieldPointIndex(int i, int j, int r) { return j * (r + 1) - (j * (j - 1)) / 2 + i; }
