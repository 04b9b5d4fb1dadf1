// The display transform: linear radiance -> display values in [0,1]. Applied once, at output
// (PNG, the viewer's window, the benchmark's images); every renderer writes linear radiance.
//
// ONE text, two compilers: GLSL 4.50 in shaders/display/encode.frag, and C++20 (glm) in
// src/display.cpp, which defines SSS_CPP and includes this file (as shaders/common/dirpole.glsl).
//
//   1. exposure: colour * 2^exposure (stops);
//   2. tone mapping: 0 none (clip at 1), 1 filmic: the ACES filmic fit of Narkowicz (2015),
//      x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14), clipped to [0,1];
//   3. encoding: 1 the sRGB transfer function (IEC 61966-2-1), 0 none (linear output).
// `real` is float in GLSL and double in C++; literals are floating point only.

#ifndef SSS_CPP
#ifndef real
#define real float
#endif
#endif

real displayToneMap(real x, int toneMap) {
    x = x > 0.0 ? x : 0.0;  // negative and NaN -> 0
    if (toneMap == 1) x = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
    return min(x, 1.0);
}

real displayEncodeSrgb(real x) {
    return x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055;
}

real displayChannel(real linear, real exposureScale, int toneMap, int srgb) {
    real x = displayToneMap(linear * exposureScale, toneMap);
    return srgb == 1 ? displayEncodeSrgb(x) : x;
}
