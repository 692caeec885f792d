// The OBJ reader's implementation, compiled from its header into the physics library in the
// sanitizer and fuzz builds, so that AddressSanitizer, UndefinedBehaviorSanitizer and the
// fuzzers' coverage see inside it too (the packaged shared library is built without them).
// Normal builds link the packaged library instead (physics/CMakeLists.txt).
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
