// Lambert diffuse + Blinn-Phong specular for one light (the thesis's "scattering off" model).
// n, l, v are unit vectors (normal, towards light, towards viewer).
vec3 blinnPhong(vec3 n, vec3 l, vec3 v, vec3 radiance, vec3 diffuse, vec3 specular, float shininess) {
    float nDotL = max(dot(n, l), 0.0);
    if (nDotL <= 0.0) return vec3(0.0);
    vec3 h = normalize(l + v);
    float spec = pow(max(dot(n, h), 0.0), shininess);
    return radiance * (diffuse * nDotL + specular * spec);
}
