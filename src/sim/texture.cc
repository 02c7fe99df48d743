#include "texture.h"

#include <cmath>

namespace fusemap {
namespace sim {
namespace {

uint64_t Mix(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

int64_t FloorDiv(double value, double step) { return static_cast<int64_t>(std::floor(value / step)); }

Eigen::Vector3f Lerp(const Eigen::Vector3f& a, const Eigen::Vector3f& b, double f) {
  return a + static_cast<float>(f) * (b - a);
}

// A saturated colour from a hash, for poster shapes.
Eigen::Vector3f VividColor(uint64_t a, uint64_t b, uint64_t c) {
  const double h = HashToUnit(a, b, c) * 6.0;
  const int sector = static_cast<int>(h);
  const float f = static_cast<float>(h - sector);
  const float lo = 30.f, hi = 230.f, up = lo + f * (hi - lo), down = hi - f * (hi - lo);
  switch (sector % 6) {
    case 0: return {hi, up, lo};
    case 1: return {down, hi, lo};
    case 2: return {lo, hi, up};
    case 3: return {lo, down, hi};
    case 4: return {up, lo, hi};
    default: return {hi, lo, down};
  }
}

Eigen::Vector3f Brick(const Texture& t, double u, double v) {
  const double h = t.scale_m;
  const double w = 2.0 * t.scale_m;
  const int64_t row = FloorDiv(v, h);
  const double shifted_u = u + (row % 2 != 0 ? 0.5 * w : 0.0);
  const int64_t col = FloorDiv(shifted_u, w);
  const double fu = shifted_u - col * w;
  const double fv = v - row * h;
  const double mortar = 0.08 * h;
  if (fu < mortar || fv < mortar) return Eigen::Vector3f(215.f, 210.f, 200.f);
  return Lerp(t.color_a, t.color_b, HashToUnit(t.seed, row, col));
}

Eigen::Vector3f Poster(const Texture& t, double u, double v) {
  const double panel_w = 4.0 * t.scale_m;
  const int64_t panel = FloorDiv(u, panel_w);
  const double pu = u - panel * panel_w;
  // Poster occupies most of the panel within the texture's height band.
  const double margin = 0.1 * panel_w;
  const double bottom = t.band_bottom_m, top = t.band_top_m;
  if (pu < margin || pu > panel_w - margin || v < bottom || v > top) return t.color_a;
  if (pu < margin + 0.02 || pu > panel_w - margin - 0.02 || v < bottom + 0.02 || v > top - 0.02) {
    return t.color_b;  // Frame.
  }
  const double x = (pu - margin) / (panel_w - 2.0 * margin);
  const double y = (v - bottom) / (top - bottom);
  Eigen::Vector3f color = Lerp(Eigen::Vector3f(245.f, 240.f, 225.f), t.color_a, 0.2);
  // A few seeded rectangles and discs, painted in order (later ones on top).
  for (uint64_t k = 0; k < 6; ++k) {
    const double cx = HashToUnit(t.seed, panel, 10 * k + 1);
    const double cy = HashToUnit(t.seed, panel, 10 * k + 2);
    const double size = 0.08 + 0.25 * HashToUnit(t.seed, panel, 10 * k + 3);
    const bool disc = HashToUnit(t.seed, panel, 10 * k + 4) < 0.4;
    const double dx = x - cx, dy = (y - cy) * (top - bottom) / (panel_w - 2.0 * margin);
    const bool inside = disc ? dx * dx + dy * dy < size * size * 0.5
                             : std::abs(dx) < size && std::abs(dy) < 0.6 * size;
    if (inside) color = VividColor(t.seed, panel, k);
  }
  return color;
}

}  // namespace

double HashToUnit(uint64_t a, uint64_t b, uint64_t c) {
  const uint64_t h = Mix(Mix(Mix(a) ^ b) ^ c);
  return static_cast<double>(h >> 11) * (1.0 / 9007199254740992.0);
}

Eigen::Vector3f SampleTexture(const Texture& t, double u, double v) {
  switch (t.kind) {
    case Texture::Kind::kPlain:
      return t.color_a;
    case Texture::Kind::kBrick:
      return Brick(t, u, v);
    case Texture::Kind::kNoise: {
      // Blocky value noise over two scales: many corners for ORB, no repetition.
      const double coarse = HashToUnit(t.seed, FloorDiv(u, t.scale_m), FloorDiv(v, t.scale_m));
      const double fine =
          HashToUnit(t.seed + 1, FloorDiv(u, 0.37 * t.scale_m), FloorDiv(v, 0.37 * t.scale_m));
      return Lerp(t.color_a, t.color_b, 0.65 * coarse + 0.35 * fine);
    }
    case Texture::Kind::kStripes: {
      const int64_t stripe = FloorDiv(u, t.scale_m);
      const bool band = std::fmod(std::abs(v), 1.0) < 0.12;
      const bool dark = (stripe % 2 != 0) != band;
      return dark ? t.color_b : Lerp(t.color_a, t.color_b, 0.3 * HashToUnit(t.seed, stripe, 0));
    }
    case Texture::Kind::kPoster:
      return Poster(t, u, v);
    case Texture::Kind::kChecker: {
      const bool odd = ((FloorDiv(u, t.scale_m) + FloorDiv(v, t.scale_m)) & 1) != 0;
      return odd ? t.color_b : t.color_a;
    }
  }
  return t.color_a;
}

bool TextureKindFromName(const std::string& name, Texture::Kind* kind) {
  if (name == "plain") *kind = Texture::Kind::kPlain;
  else if (name == "brick") *kind = Texture::Kind::kBrick;
  else if (name == "noise") *kind = Texture::Kind::kNoise;
  else if (name == "stripes") *kind = Texture::Kind::kStripes;
  else if (name == "poster") *kind = Texture::Kind::kPoster;
  else if (name == "checker") *kind = Texture::Kind::kChecker;
  else return false;
  return true;
}

}  // namespace sim
}  // namespace fusemap
