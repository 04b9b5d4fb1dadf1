/* Linked into programs that create GL contexts, in SSS_SANITIZE builds only.
 * Mesa's llvmpipe leaves a few small allocations at exit whose stacks end in its JIT-compiled
 * code ("<unknown module>"), so LeakSanitizer can neither attribute nor suppress them by
 * library. Leak checking is therefore off in GL processes; address and undefined-behaviour
 * checks stay on, and the CPU-only test binary keeps leak checking. */
const char* __asan_default_options(void);
const char* __asan_default_options(void) { return "detect_leaks=0"; }
