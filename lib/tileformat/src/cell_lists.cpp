// The ids and cluster-grid lists of line and point tiles (see cell_lists.hpp).
#include "internal/cell_lists.hpp"

#include <string>

#include "tileformat/error.hpp"

namespace tileformat {

void write_increasing_ids(ByteWriter& out, std::span<const uint64_t> ids, const char* section,
                          const char* what) {
  for (size_t i = 0; i < ids.size(); ++i) {
    if (i > 0 && ids[i] <= ids[i - 1])
      throw FormatError(section, std::string(what) + " ids not strictly increasing");
    out.varint(ids[i] - (i ? ids[i - 1] + 1 : 0));
  }
}

std::vector<uint64_t> read_increasing_ids(ByteReader& r, uint32_t count, const char* what) {
  std::vector<uint64_t> ids(count);
  uint64_t prev = 0;
  for (uint32_t i = 0; i < count; ++i) {
    const uint64_t d = r.varint();
    const uint64_t id = i ? prev + 1 + d : d;
    if (i && id <= prev) r.fail(std::string(what) + " id overflow");
    ids[i] = prev = id;
  }
  return ids;
}

void write_cell_lists(ByteWriter& out, const std::vector<uint32_t>& offsets,
                      const std::vector<uint32_t>& items) {
  const size_t cells = offsets.size() - 1;
  for (size_t c = 0; c < cells; ++c)
    out.varint(offsets[c + 1] - offsets[c]);
  for (size_t c = 0; c < cells; ++c)
    for (uint32_t k = offsets[c]; k < offsets[c + 1]; ++k)
      out.varint(k == offsets[c] ? items[k] : items[k] - items[k - 1] - 1);
}

void read_cell_lists(ByteReader& r, size_t cells, uint32_t entries, uint32_t item_count,
                     const char* item_name, std::vector<uint32_t>& offsets,
                     std::vector<uint32_t>& items) {
  offsets.assign(cells + 1, 0);
  for (size_t c = 0; c < cells; ++c) {
    const uint64_t n = r.varint();
    if (n > entries || offsets[c] + n > entries) r.fail("cell counts exceed the entry count");
    offsets[c + 1] = static_cast<uint32_t>(offsets[c] + n);
  }
  if (offsets[cells] != entries) r.fail("cell counts do not sum to the entry count");
  items.resize(entries);
  for (size_t c = 0; c < cells; ++c) {
    uint64_t s = 0;
    for (uint32_t k = offsets[c]; k < offsets[c + 1]; ++k) {
      const uint64_t d = r.varint();
      if (d >= item_count) r.fail("cell entry out of range");
      s = k == offsets[c] ? d : s + 1 + d;
      if (s >= item_count)
        r.fail(std::string("cell lists ") + item_name + " " + std::to_string(s) + " of " +
               std::to_string(item_count));
      items[k] = static_cast<uint32_t>(s);
    }
  }
}

}  // namespace tileformat
