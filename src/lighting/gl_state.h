#pragma once
// The GL state contract of every libsss pass (mesh, volume, hybrid, display), checked by
// tests/gl/test_hybrid.cpp ("every renderer leaves the GL state it found").
//
// A pass may assume, and must leave behind:
//  - no program in use (glUseProgram(0)) and no vertex array bound;
//  - blending and face culling disabled;
//  - depth test function GL_LESS with depth writes on (whether the depth test is enabled is
//    each pass's own choice: it sets it before drawing);
//  - colour writes on for every channel.
// A pass sets everything else it relies on before it draws: framebuffer and viewport, depth-test
// enable, blend function, the texture units of src/lighting/texture_units.h it samples, image
// and storage-buffer bindings (which it unbinds when other passes could read stale ones).
// Textures and buffers stay bound to their units after a pass: the next pass binds its own.
