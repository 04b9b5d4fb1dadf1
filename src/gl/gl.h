#pragma once
// The one place the GL loader is included. Everything GL-specific in libsss is internal; public
// headers never mention GL types.
#include <glad/gl.h>
