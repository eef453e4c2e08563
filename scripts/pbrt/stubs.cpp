// Symbols the link of pixel_samplers.cpp needs from pbrt's printing and logging, which the
// samplers' sampling paths never call: each aborts if it ever is.
#include <pbrt/util/error.h>
#include <pbrt/util/log.h>
#include <pbrt/util/rng.h>

#include <cstdlib>

namespace pbrt {
void LogFatal(LogLevel, const char *, int, const char *) { std::abort(); }
std::string RNG::ToString() const { std::abort(); }
void Warning(const FileLoc *, const char *) {}
namespace detail {
std::string FloatToString(float) { std::abort(); }
std::string copyToFormatString(const char **, std::string *) { std::abort(); }
void stringPrintfRecursive(std::string *, const char *) { std::abort(); }
}  // namespace detail
namespace internal {
template <typename T>
std::string ToString2(T, T);
template <typename T>
std::string ToString3(T, T, T);
template <> std::string ToString2<float>(float, float) { std::abort(); }
template <> std::string ToString3<float>(float, float, float) { std::abort(); }
}  // namespace internal
}  // namespace pbrt

