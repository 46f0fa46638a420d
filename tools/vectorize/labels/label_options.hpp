// The label options every vector build shares (--label-field,
// --priority-field; docs/labels.md), declared once.
#pragma once

#include "labels/label_candidates.hpp"
#include "runtime/cli_args.hpp"

namespace globe {

// `what`: what one label names ("a polygon", "a place", "a line"), for --help.
void declare_label_options(CliArgs& cli, LabelOptions& o, const char* what);

}  // namespace globe
