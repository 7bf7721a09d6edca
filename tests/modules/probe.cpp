// Compiled by tests/modules/CMakeLists.txt with PROBE_HEADER naming one header, as a source of
// the module under test would include it.
#include PROBE_HEADER
