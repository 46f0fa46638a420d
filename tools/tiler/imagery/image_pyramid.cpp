// Image pyramid step (see image_pyramid.hpp).
#include "imagery/image_pyramid.hpp"

namespace globe {

TilePixels downsample_children(const std::array<const TilePixels*, 4>& children, int size,
                               int colour) {
  TilePixels out(size, colour);
  const int half = size / 2;
  uint8_t* out_alpha = out.plane(colour);
  for (int c = 0; c < 4; ++c) {
    const TilePixels* kid = children[c];
    if (!kid) continue;
    const int ox = (c & 1) * half, oy = (c >> 1) * half;
    const uint8_t* a = kid->alpha();
    for (int y = 0; y < half; ++y)
      for (int x = 0; x < half; ++x) {
        const size_t s00 = size_t(2 * y) * size + 2 * x, s01 = s00 + 1, s10 = s00 + size,
                     s11 = s10 + 1;
        const uint32_t a_sum = uint32_t{a[s00]} + a[s01] + a[s10] + a[s11];
        const size_t d = size_t(oy + y) * size + ox + x;
        out_alpha[d] = static_cast<uint8_t>((a_sum + 2) / 4);
        if (a_sum == 0) continue;
        for (int b = 0; b < colour; ++b) {
          const uint8_t* p = kid->plane(b);
          const uint32_t sum = uint32_t{p[s00]} * a[s00] + uint32_t{p[s01]} * a[s01] +
                               uint32_t{p[s10]} * a[s10] + uint32_t{p[s11]} * a[s11];
          out.plane(b)[d] = static_cast<uint8_t>((sum + a_sum / 2) / a_sum);
        }
      }
  }
  return out;
}

}  // namespace globe
