// Lambert diffuse + Blinn-Phong specular for one light (the thesis's "scattering off" model).
// n, l, v are unit vectors (normal, towards light, towards viewer).

// x^shininess for x >= 0. A program compiled with INTEGER_SHININESS n (1..256) raises to the
// constant n by repeated squaring: the loop unrolls and its tests fold away, leaving a few
// multiplications where pow() costs a logarithm and an exponential. Exact for whole exponents.
float specularPower(float x, float shininess) {
#if defined(INTEGER_SHININESS) && INTEGER_SHININESS > 0
    float result = 1.0;
    float base = x;
    for (int bit = 0; bit < 9; ++bit) {
        if (((INTEGER_SHININESS >> bit) & 1) != 0) result *= base;
        base *= base;
    }
    return result;
#else
    return pow(x, shininess);
#endif
}

// The same from the cosines n . l and n . h (h = normalize(l + v)), for callers that have them
// without n (the ray caster's gradient normals).
vec3 blinnPhongCosines(float nDotL, float nDotH, vec3 radiance, vec3 diffuse, vec3 specular, float shininess) {
    if (nDotL <= 0.0) return vec3(0.0);
    float spec = specularPower(max(nDotH, 0.0), shininess);
    return radiance * (diffuse * nDotL + specular * spec);
}

vec3 blinnPhong(vec3 n, vec3 l, vec3 v, vec3 radiance, vec3 diffuse, vec3 specular, float shininess) {
    return blinnPhongCosines(dot(n, l), dot(n, normalize(l + v)), radiance, diffuse, specular, shininess);
}
