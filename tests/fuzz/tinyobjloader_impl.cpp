// tinyobjloader's implementation, compiled from the installed header (libtinyobjloader-dev)
// with the fuzzer's instrumentation, so that libFuzzer sees coverage inside the OBJ parser.
// Same header and settings (float real_t) as the packaged libtinyobjloader that libsss links.
// Off with -DSSS_FUZZ_INSTRUMENT_TINYOBJLOADER=OFF (the target then links the package's library).
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
