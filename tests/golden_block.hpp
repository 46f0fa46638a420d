// The content of tests/data/golden_mblock_v1.bin: a 33 x 33 block given by a
// fixed formula. make_golden_mblock writes it; mblock_codec_test decodes it.
#pragma once

#include "tileformat/kpatch.hpp"
#include "tileformat/mblock.hpp"

inline tileformat::MBlock golden_block() {
  tileformat::MBlock b;
  b.size = 33;
  b.lattice = 16;
  b.step = 0.5;
  for (int y = 0; y < 33; ++y)
    for (int x = 0; x < 33; ++x)
      b.q.push_back((x * x - 7 * y) % 97 - 40);
  b.valid.assign(b.q.size(), 1);
  for (int i = 0; i < 33; ++i)
    b.valid[size_t(i) * 33 + i] = 0;
  b.vertex_error.resize(tileformat::kpatch_vertex_count(2));
  for (size_t i = 0; i < b.vertex_error.size(); ++i)
    b.vertex_error[i] = static_cast<uint32_t>(i * 3);
  return b;
}
