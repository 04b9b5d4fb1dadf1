// Depth pre-pass: only depth is written (colour writes are masked off).
void main() {}
