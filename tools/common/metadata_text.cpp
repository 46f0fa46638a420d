// Metadata number formatting (see metadata_text.hpp).
#include "metadata_text.hpp"

#include <charconv>
#include <sstream>

namespace globe {

std::string metadata_number(double v, int digits) {
  if (digits == 0) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
  }
  std::ostringstream o;
  o.precision(digits);
  o << v;
  return o.str();
}

std::string metadata_bounds(const tileformat::Bounds& ll, const tileformat::Bounds& lim,
                            int digits) {
  auto one = [&](double v, double lo, double hi) {
    const std::string text = metadata_number(v, digits);
    const double back = std::stod(text);
    if (back < lo) return metadata_number(lo, 0);
    if (back > hi) return metadata_number(hi, 0);
    return text;
  };
  return one(ll.min_x, lim.min_x, lim.max_x) + "," + one(ll.min_y, lim.min_y, lim.max_y) + "," +
         one(ll.max_x, lim.min_x, lim.max_x) + "," + one(ll.max_y, lim.min_y, lim.max_y);
}

}  // namespace globe
