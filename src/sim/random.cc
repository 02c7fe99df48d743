#include "random.h"

#include "texture.h"

namespace fusemap {
namespace sim {

std::mt19937_64 MakeRng(uint64_t seed, NoiseStream stream, uint64_t index) {
  const double u = HashToUnit(seed, static_cast<uint64_t>(stream), index);
  return std::mt19937_64(static_cast<uint64_t>(u * 18446744073709551615.0) ^ seed);
}

}  // namespace sim
}  // namespace fusemap
