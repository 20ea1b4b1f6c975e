// cpp-httplib (the client side of the API: the CLI and the tests), included through one place.
#pragma once

#include <httplib.h>

// httplib pulls in glibc's <resolv.h>, which defines `_res` as a macro for the legacy resolver
// state. Eigen (through core/) names function parameters `_res`, so any translation unit that
// sees both would not compile. Nothing here uses the legacy resolver.
#ifdef _res
#undef _res
#endif
