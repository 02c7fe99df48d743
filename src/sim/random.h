#ifndef FUSEMAP_SIM_RANDOM_H_
#define FUSEMAP_SIM_RANDOM_H_

#include <cstdint>
#include <random>

namespace fusemap {
namespace sim {

// Noise streams: every message draws from its own generator seeded by (seed, stream, index),
// so results do not depend on the order (or thread) in which messages are simulated.
enum class NoiseStream : uint64_t { kLaser = 1, kOdometry = 2, kImu = 3, kDepth = 4, kColor = 5 };

std::mt19937_64 MakeRng(uint64_t seed, NoiseStream stream, uint64_t index);

}  // namespace sim
}  // namespace fusemap

#endif  // FUSEMAP_SIM_RANDOM_H_
