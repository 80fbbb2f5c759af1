#include "backends.hpp"

// registerBackends, one call per back-end the build has (TSR_BACKENDS).
#include "registered_backends.inc"
