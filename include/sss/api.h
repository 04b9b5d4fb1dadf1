#pragma once
/// @file
/// What a shared libsss exports. Its libraries are built with hidden visibility
/// (-fvisibility=hidden), so a shared build (BUILD_SHARED_LIBS=ON) exports the public API and
/// nothing else: not the GL loader, the passes or the other internals. Each public header puts
/// its declarations between SSS_BEGIN_API and SSS_END_API; SSS_API marks the few internal
/// functions one component calls in another (number formatting, mesh checks, light sweeps).

#if defined(__GNUC__) || defined(__clang__)
#define SSS_API __attribute__((visibility("default")))
/// For internal types a public header must name (the renderers' friends): kept hidden.
#define SSS_INTERNAL __attribute__((visibility("hidden")))
#define SSS_BEGIN_API _Pragma("GCC visibility push(default)")
#define SSS_END_API _Pragma("GCC visibility pop")
#else
#define SSS_API
#define SSS_INTERNAL
#define SSS_BEGIN_API
#define SSS_END_API
#endif
