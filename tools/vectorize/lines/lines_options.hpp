// Command-line options of every command that writes line tiles (lines,
// bundle): --style, --cluster-grid, --simplify, --memory-mb.
#pragma once

#include "lines/lines_settings.hpp"
#include "runtime/cli_args.hpp"

namespace globe {

void declare_line_tile_options(CliArgs& cli, LinesSettings& s);

}  // namespace globe
