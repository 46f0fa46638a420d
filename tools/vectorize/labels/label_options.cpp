// Label options (see label_options.hpp).
#include "labels/label_options.hpp"

#include <string>

namespace globe {

void declare_label_options(CliArgs& cli, LabelOptions& o, const char* what) {
  cli.option("--label-field", "FIELD|auto",
             std::string("store a label per feature for globe-view and the MVT exports: the\n"
                         "                              attribute naming ") +
                 what + ", or auto (the first of name, NAME, name_en, ...; default: no labels)",
             [&](const std::string& v) { o.field = v; });
  cli.option("--priority-field", "FIELD",
             "numeric attribute ranking the labels, larger first (default: the feature's size)",
             [&](const std::string& v) { o.priority = v; });
}

}  // namespace globe
