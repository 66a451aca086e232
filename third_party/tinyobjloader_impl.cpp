// tinyobjloader's implementation, compiled from Debian's own header (libtinyobjloader-dev) instead of linking its
// shared library, so that sanitizer and fuzzing builds instrument it too. Nothing is copied: the header is the
// system's. Used only when LUEUR_SANITIZE or LUEUR_FUZZ is set (see dependencies.cmake).
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
