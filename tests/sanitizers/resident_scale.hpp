#pragma once
// Tests that bound a process's resident memory measure it with the
// sanitizer of their build. ThreadSanitizer keeps shadow memory (two bytes
// of shadow per byte, GCC 12's runtime) for every page of the program's
// memory it has seen touched, so a bound on resident growth scales by 3
// under it. ASan's cost is a fixed quarantine, not a factor: tests that
// need it add it themselves.
namespace tsr::test {

#if defined(__SANITIZE_THREAD__)
inline constexpr long kResidentScale = 3;
#else
inline constexpr long kResidentScale = 1;
#endif

}  // namespace tsr::test
