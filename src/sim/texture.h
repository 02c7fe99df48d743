#ifndef FUSEMAP_SIM_TEXTURE_H_
#define FUSEMAP_SIM_TEXTURE_H_

#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "fusemap/sim/world.h"

namespace fusemap {
namespace sim {

// Deterministic integer hash to [0, 1) (a splitmix64 finaliser over the mixed inputs).
double HashToUnit(uint64_t a, uint64_t b, uint64_t c);

// RGB in 0..255 of `texture` at surface coordinates (u_m, v_m). Pure and re-entrant.
Eigen::Vector3f SampleTexture(const Texture& texture, double u_m, double v_m);

// "plain", "brick", "noise", "stripes", "poster", "checker"; false for an unknown name.
bool TextureKindFromName(const std::string& name, Texture::Kind* kind);

}  // namespace sim
}  // namespace fusemap

#endif  // FUSEMAP_SIM_TEXTURE_H_
