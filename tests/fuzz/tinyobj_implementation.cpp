// tinyobjloader compiled into the OBJ harness, so that the parser itself runs
// under coverage, ASan and UBSan: Debian's libtinyobjloader is a shared library
// built without them. The harness's definitions come before the shared
// library's at link time, so build_obj_mesh() calls these.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
