// stb_easy_font (Debian's libstb-dev), the bitmap font of the legends and the 3D text labels, included without
// its warnings (unused static functions, missing initialisers, sign compares) tripping -Werror.
// Every function is static: each source file that includes this gets its own copy.
#pragma once

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop
