// What the user chose about labels (--labels, --label-size, --label-font;
// docs/viewer.md "Labels").
#pragma once

#include <string>

namespace globe::viewer {

struct LabelSettings {
  bool enabled = true;  // --labels off: false
  std::string field;    // --labels FIELD: the attribute to show ("" the stored text)
  double size_px = 13;  // --label-size: at the view's centre distance
  std::string font;     // --label-font FILE: before Debian's fonts
};

}  // namespace globe::viewer
