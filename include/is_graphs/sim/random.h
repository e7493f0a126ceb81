#pragma once

#include <cstdint>

namespace is_graphs {
namespace sim {

/// Independent random streams of one scenario: each part of the simulation seeds its own
/// std::mt19937_64 with StreamSeed(seed, stream[, index]) so that changing one part (say, the
/// clutter) leaves the others' random numbers unchanged.
enum RandomStream : std::uint64_t {
  kStreamClutter = 1,
  kStreamScan = 2,  // index: the scan number
  kStreamOdometry = 3,
  kStreamGlass = 4,          // index: the scan number
  kStreamSensorEffects = 5,  // index: the scan number (sensor_effects.h: one sub-stream an effect)
};

/// SplitMix64 finalizer: a well-mixed 64-bit value of x.
inline std::uint64_t SplitMix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

inline std::uint64_t StreamSeed(std::uint64_t seed, std::uint64_t stream, std::uint64_t index = 0) {
  return SplitMix64(SplitMix64(SplitMix64(seed) ^ stream) ^ index);
}

}  // namespace sim
}  // namespace is_graphs
