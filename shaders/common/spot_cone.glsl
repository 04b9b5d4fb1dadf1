// A spot light's cone (C++ twin: sss::spotConeFactor in src/light.cpp). `cosines` holds the
// cosines of the outer and inner half-angles (detail::spotConeCosines); `cosAngle` is the cosine
// between the cone axis and the direction of emission. 0 outside the outer cone, 1 inside the
// inner one (and everywhere for cosines <= -1, which lights without a cone are given),
// smoothstep in the cosine between.
float spotConeFactor(vec2 cosines, float cosAngle) {
    if (cosAngle <= cosines.x) return 0.0;
    if (cosAngle >= cosines.y) return 1.0;  // also the hard edge, where both cosines are equal
    float t = (cosAngle - cosines.x) / (cosines.y - cosines.x);
    return t * t * (3.0 - 2.0 * t);
}
